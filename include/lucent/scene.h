// scene.h: a scene in memory and how to load one. Scene files are JSON (see docs/scene-format.md).
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "lucent/material.h"
#include "lucent/mesh.h"
#include "lucent/params.h"

namespace lucent {

struct Camera {
  glm::vec3 eye{0.0f, 0.0f, 5.0f};     // [scene units]
  glm::vec3 target{0.0f};              // [scene units]
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fov_y_deg = 40.0f;             // vertical field of view [degrees]
  glm::mat4 view_from_world() const;
  glm::mat4 clip_from_view(float aspect, float z_near, float z_far) const;
};

struct DirectionalLight {
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // unit direction the light travels (world)
  glm::vec3 radiance{1.0f};                // RGB radiance-times-solid-angle, i.e. irradiance on a surface facing it
  bool specular = true;                    // GGX highlight (off for lights standing in for an environment map,
                                           // whose specular reflection is looked up in the map itself)
};

// A point light, or a spot light when `spot` is set. Radiant intensity in W/sr: a surface facing the light at
// distance d receives the irradiance I / d^2 with d in metres (scene units times scale_mm / 1000), in the same
// units as a directional light's `radiance`.
struct PointLight {
  glm::vec3 position{0.0f};                 // [scene units]
  glm::vec3 intensity{1.0f};                // RGB radiant intensity [W/sr]
  bool spot = false;
  glm::vec3 direction{0.0f, -1.0f, 0.0f};   // spot: unit axis, the direction the light travels
  float inner_deg = 30.0f;                  // spot: full intensity within this half-angle [degrees]
  float outer_deg = 45.0f;                  // spot: no light beyond this half-angle [degrees]
};

// A point light's intensity in scene units: the irradiance on a surface facing it at distance d (scene units)
// is intensity_in_scene_units(light, scale_mm) / d^2.
inline glm::vec3 intensity_in_scene_units(const PointLight& light, float scale_mm) {
  float units_per_metre = 1000.0f / scale_mm;
  return light.intensity * (units_per_metre * units_per_metre);
}

struct EnvironmentMap;  // lucent/environment.h

// Environment lighting (Dal Corso et al. 2015, Section 4, Fig. 15): the map is importance-sampled into M
// directional lights when the scene loads (appended to Scene::lights), and the renderer adds the specular
// reflection of the map with Fresnel reflectance.
struct EnvironmentLight {
  std::string file;                          // the .hdr or .exr equirectangular map, as resolved
  int light_count = 8;                       // M
  float intensity = 1.0f;                    // scale applied to the map's radiance
  bool background = true;                    // camera rays that miss everything see the map
  std::shared_ptr<const EnvironmentMap> map; // the loaded map, already scaled
};

// A per-frame vertex deformation in object space (y up), the "melting or bending object" of Dal Corso et al.:
// nothing is precomputed; the method re-renders its maps from the deformed mesh every frame.
enum class DeformationType { None, Bend, Melt, Wave };
struct Deformation {
  DeformationType type = DeformationType::None;
  float amplitude = 0.3f;  // bend, wave: sideways displacement at the top [object units]; melt: height lost [0, 1)
  float period_s = 4.0f;   // one cycle [seconds]
  float start_s = 0.0f;    // time in the cycle at render time 0 [seconds]
};

// The multipole model's thickness per surface point, measured on the mesh (a material's "thickness_from_mesh"):
// values on the nodes of a grid over the object's world-space box, interpolated trilinearly over the nodes near
// the surface (geometry/thickness_field.h). Empty: the material's one thickness_mm everywhere.
struct ThicknessGrid {
  glm::vec3 origin{0.0f};     // the first node [scene units]
  float cell = 0.0f;          // node spacing [scene units]
  glm::ivec3 nodes{0};        // node counts along x, y, z
  std::vector<float> values;  // [scene units], x fastest; 0 where no surface is near
  float fallback = 0.0f;      // where no node near a point has a value: the area-weighted median [scene units]
  bool empty() const { return values.empty(); }
};

struct SceneObject {
  std::string name;
  Deformation deformation;            // per-frame vertex animation (none by default)
  int blob_resolution = 0;            // > 0: the animated implicit blob surface (geometry/blob_field.h), extracted
                                      // on the GPU every frame on a grid of this many cells along its long axis
  TriangleMesh mesh;                  // object space
  std::string mesh_file;              // the file the mesh was read from (empty for procedural shapes)
  glm::mat4 world_from_object{1.0f};
  std::optional<Material> material;   // translucent when set
  glm::vec3 albedo{0.8f};             // diffuse reflectance of an opaque object
  ThicknessGrid thickness;            // the multipole model's thickness per point (from the mesh), or empty
  bool translucent() const { return material.has_value(); }
  bool animated() const { return deformation.type != DeformationType::None || blob_resolution > 0; }
};

enum class ToneMapOperator { Linear = 0, Reinhard = 1, Aces = 2 };

struct RenderSettings {
  int width = 640;
  int height = 480;
  int frames = 1;               // frames accumulated by `lucent render`
  std::uint64_t seed = 1;       // render.seed and --seed take 32 bits; the GPU reference all 64 of its --seed
  float exposure = 0.0f;        // [stops]
  ToneMapOperator tonemap = ToneMapOperator::Aces;
  glm::vec3 background{0.0f};   // radiance behind the scene
  float fps = 30.0f;            // animation: seconds per frame = 1 / fps (lucent render --animate)
};

struct Scene {
  std::string source = "<built-in default>";  // file the scene came from, for messages
  float scale_mm = 1.0f;                        // millimetres per scene unit
  Camera camera;
  std::vector<DirectionalLight> lights;
  std::vector<PointLight> point_lights;         // point and spot lights
  std::optional<EnvironmentLight> environment;
  std::vector<SceneObject> objects;
  // Where the scene file's coordinate origin lies in the Scene's coordinates, negated: a position p in the file is
  // p - origin here [scene units]. Zero unless the camera looks at a point far from the file's origin relative to
  // its distance to it (more than kFarFromOrigin times): the loader then moves the origin to the camera's target, in
  // double precision, so that float keeps its resolution where the objects are (a 2 cm ball 10 km from the origin
  // would otherwise be 1 mm grids of vertices and rays). Writers add it back.
  glm::dvec3 origin{0.0};
  std::string method;                           // a registered method (`lucent methods`); empty: the default
  ParamValues method_params;                    // declared by the method (see `lucent render --help`)
  RenderSettings render;
  // The denoising stage after the method (the scene's "denoise" object; declarations in src/denoise/
  // denoise_params.h): off unless its "enabled" is true. Empty values are the defaults.
  ParamValues denoise;
};

// A camera target farther from the file's origin than this many times the camera's distance to it moves the
// origin there (Scene::origin).
inline constexpr double kFarFromOrigin = 16.0;

// Loads a scene file. `overrides` are "key.path=value" strings (value as JSON, or a bare string) applied to
// the JSON before validation, e.g. "method.K=8", "render.width=320", "objects.0.material=Potato".
// Throws lucent::Error naming the file and the JSON path of the offending key.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});
// Same, from JSON text; `source` names it in messages, relative mesh paths resolve against `base_dir`.
Scene parse_scene(const std::string& json_text, const std::string& source, const std::string& base_dir,
                  const std::vector<std::string>& overrides = {});
// The built-in default scene (procedural, needs no file).
const char* default_scene_json();
Scene default_scene(const std::vector<std::string>& overrides = {});

// The object-space mesh of a deforming object at time t (normals recomputed from the deformed faces).
TriangleMesh deformed_mesh(const TriangleMesh& mesh, const Deformation& deformation, double seconds);
// The scene frozen at time t: deformations applied and blob surfaces extracted (on the CPU) into plain meshes,
// e.g. for the CPU references of an animated scene.
Scene scene_at_time(const Scene& scene, double seconds);

// Whether any object's material is textured (Material::maps).
bool has_material_maps(const Scene& scene);
// Throws lucent::Error("<scene>: /objects/<i>/material: ...") for a textured material that a renderer cannot use as
// it stands: on a mesh without texture coordinates (or a blob surface), with the tabulated model, or whose
// coefficients, g, eta or model were changed after its maps were made (the maps hold texels inverted with them;
// change them in the scene file). The loader never makes such a scene; an edit through the API can.
void check_material_maps(const Scene& scene);

// Every file the scene was built from (the scene file, meshes, environment map, volume header and data): the
// inputs an output must never overwrite (lucent/output_file.h).
std::vector<std::string> scene_input_files(const Scene& scene);

// The declarations the parser checks, per section, for help and docs.
std::vector<ParamSection> scene_param_sections();

}  // namespace lucent
