// isosurface_draw.frag: the normal as a colour (never black, so covered pixels can be counted).
layout(location = 0) in vec3 v_normal;
layout(location = 0) out vec4 color;

void main() { color = vec4(0.5f * normalize(v_normal) + 0.5f, 1.0f); }
