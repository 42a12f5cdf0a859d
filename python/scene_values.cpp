// scene_values.cpp: see scene_values.h.
#include "scene_values.h"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "bindings.h"
#include "methods/method_info.h"

namespace lucent::python {
namespace {

py::tuple rgb(glm::vec3 v) { return py::make_tuple(decimal(v.x), decimal(v.y), decimal(v.z)); }
// A position in the scene file's coordinates (Scene::origin added back).
py::tuple at(glm::vec3 p, const glm::dvec3& origin) {
  if (origin == glm::dvec3(0.0)) return rgb(p);
  const glm::dvec3 q = glm::dvec3(p) + origin;
  return py::make_tuple(q.x, q.y, q.z);
}

py::object typed_value(const ParamDecl& decl, const ParamValue& value) {
  if (decl.type == ParamType::Int) return py::int_(std::llround(std::get<double>(value)));
  if (decl.type == ParamType::Vec2) {
    const glm::vec3 v = std::get<glm::vec3>(value);
    return py::make_tuple(v.x, v.y);
  }
  return std::visit(
      [](const auto& v) -> py::object {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, glm::vec3>) {
          return rgb(v);
        } else if constexpr (std::is_same_v<T, std::vector<glm::vec3>>) {
          py::list list;
          for (const glm::vec3& p : v) list.append(rgb(p));
          return list;
        } else {
          return py::cast(v);
        }
      },
      value);
}

// Items in order, found by index or name (the scene file's "name"): scene.objects[0], scene.objects["bunny"].
class SceneItems {
 public:
  SceneItems(std::string what, std::vector<std::pair<std::string, py::object>> items)
      : what_(std::move(what)), items_(std::move(items)) {}

  py::object at(const py::handle& key) const {
    if (py::isinstance<py::str>(key)) {
      const std::string name = key.cast<std::string>();
      for (const auto& [item_name, item] : items_)
        if (item_name == name) return item;
      throw py::key_error(fmt::format("no {} named '{}'; names: {}", what_, name, fmt::join(names(), ", ")));
    }
    if (py::isinstance<py::bool_>(key) || !py::hasattr(key, "__index__"))
      throw py::type_error(fmt::format("{} are indexed by position (int) or name (str), not {}", what_,
                                       py::repr(key).cast<std::string>()));
    const auto n = static_cast<long long>(items_.size());
    long long i = key.cast<long long>();
    if (i < 0) i += n;
    if (i < 0 || i >= n) throw py::index_error(fmt::format("{} index {} out of range ({} of them)", what_,
                                                           key.cast<long long>(), n));
    return items_[static_cast<std::size_t>(i)].second;
  }
  bool contains(const std::string& name) const {
    for (const auto& item : items_)
      if (item.first == name) return true;
    return false;
  }
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& item : items_) out.push_back(item.first);
    return out;
  }
  py::list values() const {
    py::list out;
    for (const auto& item : items_) out.append(item.second);
    return out;
  }
  std::size_t size() const { return items_.size(); }
  const std::string& what() const { return what_; }

 private:
  std::string what_;
  std::vector<std::pair<std::string, py::object>> items_;
};

// One object of the scene, read-only; change it with Scene.set("objects.<name>.<key>", value).
struct ObjectView {
  std::string name;
  int index = 0;
  py::object material;  // dict, or None for an opaque object
  py::object albedo;    // (r, g, b) of an opaque object, or None
  std::string mesh_file;
  std::size_t triangles = 0;
};

py::dict material_dict(const Material& m) {
  py::dict d;
  d["name"] = m.name;
  d["model"] = std::string(to_string(m.model));
  d["sigma_a"] = rgb(m.sigma_a), d["sigma_s"] = rgb(m.sigma_s), d["g"] = rgb(m.g);
  d["sigma_s_prime"] = rgb(m.sigma_s_prime()), d["sigma_t"] = rgb(m.sigma_t());
  d["eta"] = decimal(m.eta);
  d["thickness_mm"] = decimal(m.thickness_mm);  // the multipole model's reflectance thickness (0: a half-space)
  d["textured"] = m.textured();
  d["field"] = std::string(to_string(m.field.type));
  return d;
}

py::dict light_dict(const DirectionalLight& light) {
  py::dict d;
  d["type"] = "directional", d["direction"] = rgb(light.direction), d["radiance"] = rgb(light.radiance);
  d["specular"] = light.specular;
  return d;
}

py::dict light_dict(const PointLight& light, const glm::dvec3& origin) {
  py::dict d;
  d["type"] = light.spot ? "spot" : "point", d["position"] = at(light.position, origin);
  d["intensity"] = rgb(light.intensity);
  if (light.spot) d["direction"] = rgb(light.direction), d["inner_deg"] = decimal(light.inner_deg), d["outer_deg"] = decimal(light.outer_deg);
  return d;
}

}  // namespace

double decimal(float x) { return std::stod(fmt::format("{}", x)); }

py::dict camera_dict(const Camera& camera, const glm::dvec3& origin) {
  py::dict d;
  d["eye"] = at(camera.eye, origin), d["target"] = at(camera.target, origin), d["up"] = rgb(camera.up);
  d["fov_y_deg"] = decimal(camera.fov_y_deg);
  return d;
}

const char* tonemap_name(ToneMapOperator op) {
  return op == ToneMapOperator::Aces ? "aces" : op == ToneMapOperator::Reinhard ? "reinhard" : "linear";
}

py::dict method_params_dict(const Scene& scene) {
  py::dict dict;
  const methods::MethodInfo* info = methods::find_method(scene.method);
  for (const auto& [name, value] : scene.method_params.all()) {
    const ParamDecl* decl = nullptr;
    if (info)
      for (const ParamDecl& d : info->params)
        if (d.name == name) decl = &d;
    dict[py::str(name)] = decl ? typed_value(*decl, value) : typed_value(ParamDecl(name, ParamType::Float), value);
  }
  return dict;
}

py::object objects_of(const Scene& scene) {
  std::vector<std::pair<std::string, py::object>> items;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    ObjectView view{o.name, static_cast<int>(i), py::none(), py::none(), o.mesh_file, o.mesh.indices.size() / 3};
    if (o.material) view.material = material_dict(*o.material);
    else view.albedo = rgb(o.albedo);
    items.emplace_back(o.name, py::cast(std::move(view)));
  }
  return py::cast(SceneItems("objects", std::move(items)));
}

py::object lights_of(const Scene& scene) {
  std::vector<std::pair<std::string, py::object>> items;
  for (const DirectionalLight& light : scene.lights) {
    py::dict d = light_dict(light);
    if (!light.specular && scene.environment) d["environment"] = true;  // a sample of the environment map
    items.emplace_back("", d);
  }
  for (const PointLight& light : scene.point_lights) items.emplace_back("", light_dict(light, scene.origin));
  return py::cast(SceneItems("lights", std::move(items)));
}

void bind_scene_values(py::module_& m) {
  py::class_<SceneItems>(m, "SceneItems",
                         "A scene's objects or lights in order, by index or by name: items[0], items[\"bunny\"].")
      .def("__getitem__", &SceneItems::at, py::arg("key"))
      .def("__len__", &SceneItems::size)
      .def("__contains__", &SceneItems::contains, py::arg("name"))
      .def("__iter__", [](const SceneItems& s) { return py::iter(s.values()); })
      .def("names", &SceneItems::names, "the names, in order (\"\" where none)")
      .def("__repr__", [](const SceneItems& s) {
        return fmt::format("<lucent.SceneItems {} {}>", s.what(), py::repr(s.values()).cast<std::string>());
      });
  py::class_<ObjectView>(m, "SceneObject",
                         "An object of a scene as loaded (read-only; change it with Scene.set(\"objects.<name or "
                         "index>.<key>\", value)).")
      .def_readonly("name", &ObjectView::name)
      .def_readonly("index", &ObjectView::index)
      .def_readonly("material", &ObjectView::material,
                    "dict: name, model, sigma_a, sigma_s, g, sigma_s_prime, sigma_t [mm^-1, per band], eta, "
                    "textured, field; None for an opaque object")
      .def_readonly("albedo", &ObjectView::albedo, "an opaque object's diffuse albedo; None for a translucent one")
      .def_readonly("mesh_file", &ObjectView::mesh_file, "\"\" for procedural shapes")
      .def_readonly("triangles", &ObjectView::triangles)
      .def("__repr__", [](const ObjectView& o) {
        return fmt::format("<lucent.SceneObject {} '{}' {}>", o.index, o.name,
                           o.material.is_none() ? "opaque" : "material " + py::str(o.material["name"]).cast<std::string>());
      });
}

}  // namespace lucent::python
