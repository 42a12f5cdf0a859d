// planes.comp: the least-squares plane around every fitted vertex, from its neighbours' current positions (the
// scene's vertex buffer, deformed on the CPU each frame): the plane through their centroid whose normal is the
// eigenvector of the smallest eigenvalue of their covariance C (power iteration on trace(C) I - C, started from
// the vertex normal and oriented like it). Norberg 2010 precomputes these planes once; fitting them every frame
// from fixed neighbour lists lets the mesh deform.
#include "shared/shader_io.h"
#include "methods/layered_stm/layered_stm_io.h"

layout(local_size_x = 64) in;

layout(std140, binding = LUCENT_BINDING_METHOD) uniform MethodBlock { LayeredStmGPU method; };
layout(std430, binding = LUCENT_BINDING_LSTM_VERTICES) readonly buffer VertexBlock { VertexGPU vertices[]; };
layout(std430, binding = LUCENT_BINDING_LSTM_FIT) readonly buffer FitBlock { uvec2 fit[]; };
layout(std430, binding = LUCENT_BINDING_LSTM_NEIGHBOURS) readonly buffer NeighbourBlock { uint neighbours[]; };
layout(std430, binding = LUCENT_BINDING_LSTM_PLANES) writeonly buffer PlaneBlock { LstmPlaneGPU planes[]; };

void main() {
  uint entry = gl_GlobalInvocationID.x;
  if (entry >= uint(method.counts.w)) return;
  uint vertex = fit[entry].x;
  uint first = fit[entry].y, last = fit[entry + 1u].y;
  vec3 origin = vertices[vertex].position.xyz;
  vec3 n0 = normalize(vertices[vertex].normal.xyz);
  vec3 sum = vec3(0.0f);
  // loop bound: param.max_neighbours; build_neighbours thins every vertex's list to max_neighbours
  for (uint i = first; i < last; ++i) sum += vertices[neighbours[i]].position.xyz - origin;
  float count = max(float(last - first), 1.0f);
  vec3 mean = sum / count;
  mat3 c = mat3(0.0f);
  // loop bound: param.max_neighbours; build_neighbours thins every vertex's list to max_neighbours
  for (uint i = first; i < last; ++i) {
    vec3 d = vertices[neighbours[i]].position.xyz - origin - mean;
    c += outerProduct(d, d);
  }
  c /= count;
  float trace = c[0][0] + c[1][1] + c[2][2];
  mat3 m = mat3(trace) - c;
  vec3 n = n0;
  if (trace > 0.0f)
    for (int it = 0; it < 24; ++it) {
      vec3 next = m * n;
      float len = length(next);
      if (!(len > 0.0f)) break;
      n = next / len;
    }
  if (dot(n, n0) < 0.0f) n = -n;
  planes[vertex].normal = vec4(n, 0.0f);
  planes[vertex].point = vec4(origin + mean, 1.0f);
}
