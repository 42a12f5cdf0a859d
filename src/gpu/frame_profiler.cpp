// frame_profiler.cpp: see frame_profiler.h.
#include "gpu/frame_profiler.h"

#include <algorithm>

#include "platform/gl_capabilities.h"

namespace lucent::gpu {

FrameProfiler::Pass::Pass(FrameProfiler* profiler, std::string_view name) : profiler_(profiler), group_(name) {
  if (profiler_) profiler_->begin_pass(name);
}

FrameProfiler::Pass::~Pass() {
  if (profiler_) profiler_->end_pass();
}

FrameProfiler::FrameProfiler() : flush_timestamps_(platform::timestamps_need_flush(platform::current_capabilities())) {
  for (Slot& slot : slots_) {
    glCreateBuffers(1, &slot.counters);
    glNamedBufferStorage(slot.counters, sizeof(shader::CountersGPU), nullptr, GL_DYNAMIC_STORAGE_BIT);
    label_object(GL_BUFFER, slot.counters, "frame counters");
  }
}

FrameProfiler::~FrameProfiler() {
  for (Slot& slot : slots_) {
    if (!slot.pool.empty()) glDeleteQueries(static_cast<GLsizei>(slot.pool.size()), slot.pool.data());
    if (slot.fence) glDeleteSync(slot.fence);
    glDeleteBuffers(1, &slot.counters);
  }
}

void FrameProfiler::begin_frame(std::uint64_t number) {
  current_ = (current_ + 1) % kFramesInFlight;
  in_frame_ = true;
  Slot& slot = slots_[static_cast<std::size_t>(current_)];
  if (slot.pending && ready(slot, /*wait=*/true)) finished_.push_back(read(slot));
  slot.frame = number;
  slot.pending = false;
  slot.used = 0;
  slot.queries.clear();
  const GLuint zero = 0;
  glClearNamedBufferData(slot.counters, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LUCENT_BINDING_COUNTERS, slot.counters);
}

void FrameProfiler::end_frame() {
  if (!in_frame_) return;
  in_frame_ = false;
  Slot& slot = slots_[static_cast<std::size_t>(current_)];
  if (slot.fence) glDeleteSync(slot.fence);
  slot.fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  slot.pending = true;
  glFlush();  // the fence must reach the GPU for a non-blocking poll to ever see it signalled
}

GLuint FrameProfiler::next_query(Slot& slot) {
  if (slot.used == slot.pool.size()) {
    GLuint id = 0;
    glCreateQueries(GL_TIMESTAMP, 1, &id);
    slot.pool.push_back(id);
  }
  return slot.pool[slot.used++];
}

void FrameProfiler::begin_pass(std::string_view name) {
  if (!in_frame_) return;  // passes outside a frame (diagnostics) are not timed
  Slot& slot = slots_[static_cast<std::size_t>(current_)];
  slot.queries.push_back({std::string(name), next_query(slot), 0});
  glQueryCounter(slot.queries.back().begin, GL_TIMESTAMP);
  if (flush_timestamps_) glFlush();
}

void FrameProfiler::end_pass() {
  if (!in_frame_) return;
  Slot& slot = slots_[static_cast<std::size_t>(current_)];
  slot.queries.back().end = next_query(slot);
  glQueryCounter(slot.queries.back().end, GL_TIMESTAMP);
  if (flush_timestamps_) glFlush();
}

bool FrameProfiler::ready(Slot& slot, bool wait) {
  if (!slot.fence) return true;
  GLenum status = glClientWaitSync(slot.fence, 0, 0);
  if (status == GL_TIMEOUT_EXPIRED && wait) {
    do status = glClientWaitSync(slot.fence, GL_SYNC_FLUSH_COMMANDS_BIT, 1'000'000'000);
    while (status == GL_TIMEOUT_EXPIRED);
  }
  return status == GL_ALREADY_SIGNALED || status == GL_CONDITION_SATISFIED || status == GL_WAIT_FAILED;
}

ProfiledFrame FrameProfiler::read(Slot& slot) {
  ProfiledFrame out;
  out.frame = slot.frame;
  for (const Query& q : slot.queries) {
    GLuint64 begin = 0, end = 0;
    glGetQueryObjectui64v(q.begin, GL_QUERY_RESULT, &begin);
    glGetQueryObjectui64v(q.end, GL_QUERY_RESULT, &end);
    double ms = end > begin ? static_cast<double>(end - begin) * 1e-6 : 0.0;
    auto same = std::find_if(out.passes.begin(), out.passes.end(), [&](const auto& p) { return p.first == q.pass; });
    if (same != out.passes.end()) same->second += ms;
    else out.passes.emplace_back(q.pass, ms);
  }
  glGetNamedBufferSubData(slot.counters, 0, sizeof(out.counters), &out.counters);
  slot.pending = false;
  return out;
}

std::vector<ProfiledFrame> FrameProfiler::collect(bool wait) {
  std::vector<ProfiledFrame> out = std::move(finished_);
  finished_.clear();
  // Oldest first: the slot after the current one is the oldest still in the ring.
  for (int i = 1; i <= kFramesInFlight; ++i) {
    Slot& slot = slots_[static_cast<std::size_t>((current_ + i + kFramesInFlight) % kFramesInFlight)];
    if (!slot.pending) continue;
    if (!ready(slot, wait)) break;  // later slots are newer: keep the order
    out.push_back(read(slot));
  }
  return out;
}

}  // namespace lucent::gpu
