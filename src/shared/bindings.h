// bindings.h: every buffer binding point, texture unit and image unit of the program, in one table (C++ and
// GLSL). Two kinds of slot:
//   - frame slots, bound once per frame by the renderer and read by many passes: unique across the program;
//   - pass-local ranges, bound right before a pass's draws or dispatches: the active method's own slots, the
//     GPU isosurface extractor's, the texture-space G-buffer's and the tests'. A method declares its slots in
//     its own folder inside the method range (static_assert there); ranges never overlap each other or the
//     frame slots, so a pass can never clobber what the frame bound.
// tests/cpu/test_bindings.cpp checks the table and finds every LUCENT_BINDING_/TEX_/IMAGE_ #define and
// kBinding constant in the sources inside its range.
#ifndef LUCENT_SHARED_BINDINGS_H
#define LUCENT_SHARED_BINDINGS_H

// ---- uniform buffers --------------------------------------------------------------------------------------
#define LUCENT_BINDING_FRAME 0   // FrameGPU (std140): camera, output, seeds, display, lights (shared/shader_io.h)
#define LUCENT_BINDING_METHOD 1  // the active method's own block (std140), declared in its folder
// 2-7: method range (uniform); 8-11: isosurface extractor; 12-15: the denoising stage

// ---- storage buffers --------------------------------------------------------------------------------------
#define LUCENT_BINDING_MATERIALS 1  // MaterialGPU[] (std430)
#define LUCENT_BINDING_OBJECTS 2    // ObjectGPU[] (std430)
#define LUCENT_BINDING_COUNTERS 3   // CountersGPU of the frame (std430), zeroed by the renderer each frame
#define LUCENT_BINDING_LAYER_VIEWS 4  // ViewGPU[] of the layered G-buffer pass being drawn (std430): each such pass
                                      // binds its own views (light layers, a method's maps) before drawing
#define LUCENT_BINDING_BSSRDF_TABLES 0  // float[]: the tabulated model's directory and tables (bssrdf/tabulated.h)
#define LUCENT_BINDING_MATERIAL_MAPS 31  // vec4[]: textured materials' texels (media/material_map.h)

// ---- texture units (samplers) -----------------------------------------------------------------------------
#define LUCENT_TEX_CAMERA_POSITION 0
#define LUCENT_TEX_CAMERA_NORMAL 1
#define LUCENT_TEX_CAMERA_DEPTH 2
#define LUCENT_TEX_LIGHT_POSITION 3
#define LUCENT_TEX_LIGHT_NORMAL 4
#define LUCENT_TEX_LIGHT_DEPTH 5
#define LUCENT_TEX_ENVIRONMENT 6
#define LUCENT_TEX_HDR 7  // the frame's radiance, read by the tone-mapping pass
#define LUCENT_TEX_CAMERA_UV 23  // the camera G-buffer's texture coordinates (scenes with textured materials only)

// ---- image units ------------------------------------------------------------------------------------------
#define LUCENT_IMAGE_HDR 0  // the frame's radiance (RGBA32F), written by the method's final pass
#define LUCENT_IMAGE_LDR 1  // the tone-mapped frame (RGBA8)

// ---- pass-local ranges (first, last), inclusive -----------------------------------------------------------
#define LUCENT_METHOD_UNIFORM_FIRST 2
#define LUCENT_METHOD_UNIFORM_LAST 7
#define LUCENT_METHOD_STORAGE_FIRST 20
#define LUCENT_METHOD_STORAGE_LAST 29
#define LUCENT_METHOD_TEX_FIRST 8
#define LUCENT_METHOD_TEX_LAST 22
#define LUCENT_METHOD_IMAGE_FIRST 2
#define LUCENT_METHOD_IMAGE_LAST 5

#define LUCENT_ISOSURFACE_UNIFORM_FIRST 8
#define LUCENT_ISOSURFACE_UNIFORM_LAST 11
#define LUCENT_ISOSURFACE_STORAGE_FIRST 8
#define LUCENT_ISOSURFACE_STORAGE_LAST 19

#define LUCENT_TEXTURE_SPACE_STORAGE_FIRST 5
#define LUCENT_TEXTURE_SPACE_STORAGE_LAST 7
#define LUCENT_TEXTURE_SPACE_TEX_FIRST 24
#define LUCENT_TEXTURE_SPACE_TEX_LAST 31
#define LUCENT_TEXTURE_SPACE_IMAGE_FIRST 6
#define LUCENT_TEXTURE_SPACE_IMAGE_LAST 7

// The denoising stage (src/denoise/) runs after the method's last pass and before tone mapping: its images may
// reuse the method's image units (GL guarantees only 8), never any other range's.
#define LUCENT_DENOISE_UNIFORM_FIRST 12
#define LUCENT_DENOISE_UNIFORM_LAST 15
#define LUCENT_DENOISE_TEX_FIRST 32
#define LUCENT_DENOISE_TEX_LAST 40
#define LUCENT_DENOISE_IMAGE_FIRST 2
#define LUCENT_DENOISE_IMAGE_LAST 4

#define LUCENT_TEST_STORAGE_FIRST 30
#define LUCENT_TEST_STORAGE_LAST 30
#define LUCENT_BINDING_PARITY 30  // the GPU parity test's cases and results (std430)

#if defined(__cplusplus)
namespace lucent::shader {

enum class SlotKind { Uniform, Storage, Texture, Image };

// A frame slot, or a pass-local range of slots (first..last) owned by one group.
struct SlotRange {
  const char* name;
  SlotKind kind;
  int first, last;
  bool frame;  // bound once per frame (true) or pass-local (false)
  // A pass-local range whose passes run only after this group's passes have ended for the frame (the denoising
  // stage after the method): it may share that group's slots, which both bind before use. Null: shares none.
  const char* runs_after = nullptr;
};

inline constexpr SlotRange kSlotTable[] = {
    {"LUCENT_BINDING_FRAME", SlotKind::Uniform, LUCENT_BINDING_FRAME, LUCENT_BINDING_FRAME, true},
    {"LUCENT_BINDING_METHOD", SlotKind::Uniform, LUCENT_BINDING_METHOD, LUCENT_BINDING_METHOD, true},
    {"LUCENT_BINDING_MATERIALS", SlotKind::Storage, LUCENT_BINDING_MATERIALS, LUCENT_BINDING_MATERIALS, true},
    {"LUCENT_BINDING_OBJECTS", SlotKind::Storage, LUCENT_BINDING_OBJECTS, LUCENT_BINDING_OBJECTS, true},
    {"LUCENT_BINDING_COUNTERS", SlotKind::Storage, LUCENT_BINDING_COUNTERS, LUCENT_BINDING_COUNTERS, true},
    {"LUCENT_BINDING_LAYER_VIEWS", SlotKind::Storage, LUCENT_BINDING_LAYER_VIEWS, LUCENT_BINDING_LAYER_VIEWS, true},
    {"LUCENT_BINDING_BSSRDF_TABLES", SlotKind::Storage, LUCENT_BINDING_BSSRDF_TABLES, LUCENT_BINDING_BSSRDF_TABLES,
     true},
    {"LUCENT_BINDING_MATERIAL_MAPS", SlotKind::Storage, LUCENT_BINDING_MATERIAL_MAPS, LUCENT_BINDING_MATERIAL_MAPS,
     true},
    {"LUCENT_TEX_CAMERA_POSITION", SlotKind::Texture, LUCENT_TEX_CAMERA_POSITION, LUCENT_TEX_CAMERA_POSITION, true},
    {"LUCENT_TEX_CAMERA_NORMAL", SlotKind::Texture, LUCENT_TEX_CAMERA_NORMAL, LUCENT_TEX_CAMERA_NORMAL, true},
    {"LUCENT_TEX_CAMERA_DEPTH", SlotKind::Texture, LUCENT_TEX_CAMERA_DEPTH, LUCENT_TEX_CAMERA_DEPTH, true},
    {"LUCENT_TEX_LIGHT_POSITION", SlotKind::Texture, LUCENT_TEX_LIGHT_POSITION, LUCENT_TEX_LIGHT_POSITION, true},
    {"LUCENT_TEX_LIGHT_NORMAL", SlotKind::Texture, LUCENT_TEX_LIGHT_NORMAL, LUCENT_TEX_LIGHT_NORMAL, true},
    {"LUCENT_TEX_LIGHT_DEPTH", SlotKind::Texture, LUCENT_TEX_LIGHT_DEPTH, LUCENT_TEX_LIGHT_DEPTH, true},
    {"LUCENT_TEX_ENVIRONMENT", SlotKind::Texture, LUCENT_TEX_ENVIRONMENT, LUCENT_TEX_ENVIRONMENT, true},
    {"LUCENT_TEX_HDR", SlotKind::Texture, LUCENT_TEX_HDR, LUCENT_TEX_HDR, true},
    {"LUCENT_TEX_CAMERA_UV", SlotKind::Texture, LUCENT_TEX_CAMERA_UV, LUCENT_TEX_CAMERA_UV, true},
    {"LUCENT_IMAGE_HDR", SlotKind::Image, LUCENT_IMAGE_HDR, LUCENT_IMAGE_HDR, true},
    {"LUCENT_IMAGE_LDR", SlotKind::Image, LUCENT_IMAGE_LDR, LUCENT_IMAGE_LDR, true},
    {"method uniform", SlotKind::Uniform, LUCENT_METHOD_UNIFORM_FIRST, LUCENT_METHOD_UNIFORM_LAST, false},
    {"method storage", SlotKind::Storage, LUCENT_METHOD_STORAGE_FIRST, LUCENT_METHOD_STORAGE_LAST, false},
    {"method textures", SlotKind::Texture, LUCENT_METHOD_TEX_FIRST, LUCENT_METHOD_TEX_LAST, false},
    {"method images", SlotKind::Image, LUCENT_METHOD_IMAGE_FIRST, LUCENT_METHOD_IMAGE_LAST, false},
    {"isosurface uniform", SlotKind::Uniform, LUCENT_ISOSURFACE_UNIFORM_FIRST, LUCENT_ISOSURFACE_UNIFORM_LAST, false},
    {"isosurface storage", SlotKind::Storage, LUCENT_ISOSURFACE_STORAGE_FIRST, LUCENT_ISOSURFACE_STORAGE_LAST, false},
    {"texture-space storage", SlotKind::Storage, LUCENT_TEXTURE_SPACE_STORAGE_FIRST, LUCENT_TEXTURE_SPACE_STORAGE_LAST,
     false},
    {"texture-space textures", SlotKind::Texture, LUCENT_TEXTURE_SPACE_TEX_FIRST, LUCENT_TEXTURE_SPACE_TEX_LAST, false},
    {"texture-space images", SlotKind::Image, LUCENT_TEXTURE_SPACE_IMAGE_FIRST, LUCENT_TEXTURE_SPACE_IMAGE_LAST, false},
    {"denoise uniform", SlotKind::Uniform, LUCENT_DENOISE_UNIFORM_FIRST, LUCENT_DENOISE_UNIFORM_LAST, false},
    {"denoise textures", SlotKind::Texture, LUCENT_DENOISE_TEX_FIRST, LUCENT_DENOISE_TEX_LAST, false},
    {"denoise images", SlotKind::Image, LUCENT_DENOISE_IMAGE_FIRST, LUCENT_DENOISE_IMAGE_LAST, false, "method"},
    {"test storage", SlotKind::Storage, LUCENT_TEST_STORAGE_FIRST, LUCENT_TEST_STORAGE_LAST, false},
};

// Limits the table stays within: GL 4.5's guaranteed 8 image units and 36 uniform-block bindings, and 32
// storage-buffer bindings (llvmpipe and NVIDIA offer at least that; the isosurface extractor checks the
// driver's GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS).
inline constexpr int kMaxImageUnit = 7;
inline constexpr int kMaxUniformBinding = 35;
inline constexpr int kMaxStorageBinding = 31;
inline constexpr int kMaxTextureUnit = 47;

}  // namespace lucent::shader
#endif

#endif
