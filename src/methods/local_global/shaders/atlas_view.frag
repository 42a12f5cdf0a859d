// atlas_view.frag: writes the pixel's atlas coordinates (z: object index + 1) and the interpolated vertex radiosity.
in AtlasViewData {
  vec2 uv;
  vec3 radiosity;
  flat float object_id;
} v_in;

layout(location = 0) out vec4 out_atlas;
layout(location = 1) out vec4 out_radiosity;

void main() {
  out_atlas = vec4(v_in.uv, v_in.object_id, 1.0f);
  out_radiosity = vec4(v_in.radiosity, 1.0f);
}
