// material.h: translucent materials in physical units and the measured presets compiled into the library.
#pragma once
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace lucent {

// Diffusion model used as S_d (shared C++/GLSL code in src/bssrdf/).
enum class BssrdfModel {
  StandardDipole = 0,
  DirectionalDipole = 1,
  PhotonBeamDiffusion = 2,
  BetterDipole = 3,
  Tabulated = 4,  // the medium's own half-space profile by photon transport (src/bssrdf/tabulated.h)
  Multipole = 5,  // a slab of finite thickness, reflectance and transmittance (src/bssrdf/multipole_table.h)
};
std::string_view to_string(BssrdfModel model);
// The model a material gets when it names none: the one measured closest to volumetric path tracing on the
// leaderboard's scene suite and the bunny (docs/accuracy.md, "Which model by default").
inline constexpr BssrdfModel kDefaultBssrdfModel = BssrdfModel::StandardDipole;
std::optional<BssrdfModel> parse_bssrdf_model(std::string_view name);  // "standard", "directional", "photon-beam", "better-dipole", "tabulated", "multipole"

// Where a heterogeneous medium came from when it was read from an OpenVDB file (lucent/medium_vdb.h reads it).
enum class VdbTransform { ObjectBounds, VdbWorld };
struct VdbField {
  std::string file;                                   // the .vdb file (as the loader opens it)
  std::string grid = "density";                       // name of a float grid in it
  float density_scale = 1.0f;                         // m = density_scale * value, >= 0
  VdbTransform transform = VdbTransform::ObjectBounds;
};

// A grid of density multipliers m >= 0 loaded from a file (a heterogeneous medium; lucent/medium_volume.h reads
// it). Values at voxel centres, x fastest, then y, then z; the grid spans the object's world-space bounds.
// The largest density multiplier a volume may hold. It shrinks a medium's mean free path a millionfold (0.01 mm
// becomes 1e-8 mm, far below any voxel): denser changes no image, while values near 1e20 overflowed the
// real-time methods' single-precision optical depths (a white column instead of an opaque region).
inline constexpr float kMaxDensityMultiplier = 1e6f;

struct MediumVolume {
  std::string source;           // file it came from, for messages (the JSON header)
  std::string data_file;        // the raw values the header names
  glm::ivec3 size{0};           // voxels per axis, each >= 1
  std::vector<float> values;    // size.x * size.y * size.z multipliers
  float max_value = 0.0f;       // largest value: the majorant of delta tracking
  std::optional<VdbField> vdb;  // set when resampled from an OpenVDB grid (written back as a "vdb" field)
  // Trilinear between voxel centres, clamped at the border; `unit` in [0, 1]^3 across the bounds.
  float multiplier(glm::vec3 unit) const;
};

// A heterogeneous medium: a density multiplier m(x) of the material over its object (the physics and the
// built-in fields are in src/media/heterogeneous_field.h): sigma_t(x) = m sigma_t, sigma_s(x) = min(m, 1) sigma_s.
enum class MediumFieldType { None = 0, Marble = 1, Layered = 2, Volume = 3 };
std::string_view to_string(MediumFieldType type);
struct MediumField {
  MediumFieldType type = MediumFieldType::None;
  float scale_mm = 10.0f;  // marble: vein period; layered: outer-layer thickness [mm]
  float contrast = 4.0f;   // marble, layered: m ranges over [1, 1 + contrast]
  std::string file;        // volume: the JSON header it was loaded from (as written in the scene)
  std::shared_ptr<const MediumVolume> volume;  // volume: the loaded grid
  // The world-space box the field spans. Unset: the object's world bounds as it is. scene_at_time() sets it to
  // the undeformed object's bounds, so a deforming object moves through a field fixed where it rests, in the
  // references as in voxel-paths.
  bool has_bounds = false;
  glm::vec3 bounds_lower{0.0f}, bounds_upper{0.0f};
  bool heterogeneous() const { return type != MediumFieldType::None; }
  float max_multiplier() const;  // the largest m anywhere (1 for none)
  // m at world point p of an object with world-space bounds [lower, upper]; one scene unit is scale_mm mm.
  float multiplier(glm::vec3 p, glm::vec3 lower, glm::vec3 upper, float scene_scale_mm) const;
};

// A spatially varying material from textures (src/materials/material_maps.h reads them), looked up through the
// mesh's texture coordinates (channel 0; OpenGL's origin, v = 0 at the bottom row), bilinear between texel centres,
// repeating outside [0, 1]. Each map is optional: where one is absent its base value holds everywhere.
//  - albedo_map: the surface albedo per texel (the model's flat total, as the material's "albedo"), inverted per
//    texel to the single-scattering albedo alpha = sigma_s / sigma_t, which is what is stored and interpolated;
//  - mfp_map: a factor on the mean free path per texel (so 1 / density), stored as the mean free path in mm.
// The coefficients at a point are sigma_s = alpha / mfp and sigma_a = (1 - alpha) / mfp. A renderer evaluates
// them where light leaves the surface (the exit point of S_d, the point a camera path enters the medium; see
// docs/materials.md, "Textures").
struct MaterialMaps {
  std::string albedo_file, mfp_file;  // as resolved ("" when not given)
  glm::vec3 base_alpha{0.5f};         // alpha where there is no albedo_map
  glm::vec3 base_mfp_mm{1.0f};        // mean free path where there is no mfp_map [mm]
  glm::ivec2 alpha_size{0};           // albedo_map's texels (0 when absent)
  std::vector<glm::vec3> alpha;       // alpha per texel and band, rows from v = 0 up, x fastest
  glm::ivec2 mfp_size{0};             // mfp_map's texels (0 when absent)
  std::vector<glm::vec3> mfp_mm;      // mean free path per texel and band [mm]
  glm::vec3 min_alpha{0.5f};          // the smallest alpha and mean free path over the texels, per band
  glm::vec3 min_mfp_mm{1.0f};         // [mm]
  // What the texels were made with: the material's g, eta and model, and its coefficients (the maps' mean).
  // A material whose fields differ from these no longer matches its texels (check_material_maps in scene.h).
  glm::vec3 made_with_g{0.0f};
  float made_with_eta = 1.3f;
  BssrdfModel made_with_model = kDefaultBssrdfModel;
  glm::vec3 made_with_sigma_a{0.0f}, made_with_sigma_s{0.0f};  // [mm^-1]
  glm::vec3 alpha_at(glm::vec2 uv) const;
  glm::vec3 mfp_mm_at(glm::vec2 uv) const;
  // sigma_a and sigma_s [mm^-1] at texture coordinates uv.
  void coefficients(glm::vec2 uv, glm::vec3& sigma_a, glm::vec3& sigma_s) const;
};

// A translucent material. Coefficients in mm^-1; the scene's scale_mm maps them to scene units.
struct Material {
  std::string name = "custom";
  glm::vec3 sigma_a{0.0f};  // absorption coefficient per RGB band [mm^-1]
  glm::vec3 sigma_s{0.0f};  // scattering coefficient, unreduced [mm^-1]
  glm::vec3 g{0.0f};        // Henyey-Greenstein mean cosine per band [-1, 1]
  float eta = 1.3f;         // relative refractive index n_material / n_outside
  BssrdfModel model = kDefaultBssrdfModel;
  // The thickness of the part [mm] (a sheet, a fin, an ear, a candle's wall), for the multipole model's reflectance:
  // light entering and leaving one face of a thin part is what its far face did not let through. 0: a half-space.
  // (Its transmittance takes the distance between the two faces a light path joins, bssrdf/multipole_table.h.)
  // The other models ignore it.
  float thickness_mm = 0.0f;
  MediumField field;        // homogeneous unless set (used by voxel-paths and volpath; the diffusion models ignore it)
  // Textured: coefficients per surface point (the ones above are those of the maps' mean albedo and mean free
  // path, for messages and for what needs one value, such as the references' sampling bounds).
  std::shared_ptr<const MaterialMaps> maps;
  bool textured() const { return maps != nullptr; }

  glm::vec3 sigma_s_prime() const { return sigma_s * (1.0f - g); }  // [mm^-1]
  glm::vec3 sigma_t() const { return sigma_a + sigma_s; }          // [mm^-1]
  glm::vec3 sigma_tr() const;  // effective transport coefficient sqrt(3 sigma_a sigma_t') [mm^-1]
};

// One measured material. Jensen et al. 2001 entries are reduced coefficients (sigma_s holds sigma_s', g = 0);
// Narasimhan et al. 2006 entries are unreduced with a per-band g.
struct MaterialPreset {
  const char* name;
  glm::vec3 sigma_a;  // [mm^-1]
  glm::vec3 sigma_s;  // [mm^-1] (reduced where `reduced`)
  glm::vec3 g;
  float eta;
  bool reduced;
  const char* source;  // publication
  const char* note;    // choice made where published tables disagree ("" if none)
};

std::span<const MaterialPreset> material_presets();
// Case-insensitive; spaces, '_', '-' and '&' are ignored ("white_grapefruit_juice" finds
// "White Grapefruit Juice"). nullptr when unknown.
const MaterialPreset* find_material_preset(std::string_view name);
Material material_from_preset(const MaterialPreset& preset);

// Throws lucent::Error("<where>: <field> ...") naming the offending field and the allowed range when a
// coefficient is NaN, infinite or negative, g is outside (-1, 1), eta outside [1, 3], or sigma_a or sigma_s'
// is zero in a band (the diffusion models need both positive).
void validate_material(const Material& material, const std::string& where);
// The checks of a medium that volumetric path tracing renders (volpath, random-walk): the coefficients, g and eta
// as validate_material checks them, and some extinction in every band; sigma_a or sigma_s' may be 0 (a pure
// scatterer, a band that only absorbs).
void validate_medium(const Material& material, const std::string& where);
// What the diffusion models need besides: sigma_a and sigma_s' positive in every band.
void validate_diffusion_medium(const Material& material, const std::string& where);

}  // namespace lucent
