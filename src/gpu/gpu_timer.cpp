// gpu_timer.cpp: GL_TIMESTAMP queries recycled from a pool.
#include "gpu/gpu_timer.h"

namespace lucent::gpu {

GpuTimer::~GpuTimer() {
  if (!pool_.empty()) glDeleteQueries(static_cast<GLsizei>(pool_.size()), pool_.data());
}

void GpuTimer::begin_frame() {
  active_.clear();
  used_ = 0;
}

GLuint GpuTimer::next_query() {
  if (used_ == pool_.size()) {
    GLuint id = 0;
    glCreateQueries(GL_TIMESTAMP, 1, &id);
    pool_.push_back(id);
  }
  return pool_[used_++];
}

void GpuTimer::begin(const std::string& pass) {
  active_.push_back({pass, next_query(), 0});
  glQueryCounter(active_.back().begin, GL_TIMESTAMP);
}

void GpuTimer::end() {
  active_.back().end = next_query();
  glQueryCounter(active_.back().end, GL_TIMESTAMP);
}

std::vector<std::pair<std::string, double>> GpuTimer::resolve() {
  std::vector<std::pair<std::string, double>> result;
  for (const Query& q : active_) {
    GLuint64 begin = 0, end = 0;
    glGetQueryObjectui64v(q.begin, GL_QUERY_RESULT, &begin);
    glGetQueryObjectui64v(q.end, GL_QUERY_RESULT, &end);
    double ms = end > begin ? static_cast<double>(end - begin) * 1e-6 : 0.0;
    bool merged = false;
    for (auto& [name, total] : result)
      if (name == q.pass) total += ms, merged = true;
    if (!merged) result.emplace_back(q.pass, ms);
  }
  return result;
}

}  // namespace lucent::gpu
