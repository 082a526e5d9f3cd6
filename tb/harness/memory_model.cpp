// The harness's memory model (see memory_model.hpp).
#include "memory_model.hpp"

#include <limits>
#include <stdexcept>
#include <utility>

namespace rc::harness {

namespace {

// Bytes of a record the port delivers for a section of an image (docs/memory-format.md).
uint32_t delivered_bytes(const scene::SceneImage& image, uint32_t id, uint32_t stride) {
  const auto vb = static_cast<uint32_t>(image.value_bytes());
  switch (id) {
    case spec::kImageSectionIdNodes: return static_cast<uint32_t>(spec::kKdNodeBytes);
    case spec::kImageSectionIdLists: return static_cast<uint32_t>(spec::kKdListEntryBytes);
    case spec::kImageSectionIdTriangles:
      return static_cast<uint32_t>(spec::kImageTriangleValues) * vb;
    case spec::kImageSectionIdShading:
      return static_cast<uint32_t>(spec::kImageShadingFirstValue) +
             static_cast<uint32_t>(spec::kImageShadingValues) * vb;
    default: return stride;
  }
}

std::vector<uint8_t> section_bytes(const scene::SceneImage& image, uint32_t id) {
  const scene::SectionInfo& s = image.section(id);
  const auto* first = image.bytes().data() + s.offset;
  return std::vector<uint8_t>(first, first + static_cast<size_t>(s.count) * s.stride);
}

}  // namespace

MemoryPort::MemoryPort(const scene::SceneImage& image, uint32_t section_id,
                       const MemoryParams& params, uint32_t records_per_response)
    : MemoryPort(section_bytes(image, section_id), image.section(section_id).count,
                 image.section(section_id).stride,
                 delivered_bytes(image, section_id, image.section(section_id).stride), params,
                 image.name() + ":" + scene::section_name(section_id), records_per_response) {}

MemoryPort::MemoryPort(std::vector<uint8_t> section_bytes, uint64_t count, uint32_t stride,
                       uint32_t record_bytes, const MemoryParams& params, std::string name,
                       uint32_t records_per_response)
    : params_(params),
      name_(std::move(name)),
      bytes_(std::move(section_bytes)),
      count_(count),
      stride_(stride),
      record_bytes_(record_bytes),
      records_(records_per_response),
      rng_(params.seed) {
  check_params();
  if (record_bytes_ == 0 || record_bytes_ > stride_)
    throw std::invalid_argument(name_ + ": record bytes " + std::to_string(record_bytes_) +
                                " must be in 1 .. stride (" + std::to_string(stride_) + ")");
  if (records_ == 0 || records_ > std::numeric_limits<uint32_t>::max() / record_bytes_)
    throw std::invalid_argument(name_ + ": records per response " + std::to_string(records_) +
                                " must be >= 1, and the response at most 2^32 - 1 bytes");
  if (bytes_.size() / stride_ < count_)
    throw std::invalid_argument(name_ + ": " + std::to_string(bytes_.size()) +
                                " bytes hold fewer than " + std::to_string(count_) + " records");
  begin_cycle();
}

void MemoryPort::check_params() const {
  const auto fail = [this](const std::string& what) {
    throw std::invalid_argument(name_ + ": memory parameter " + what);
  };
  const auto prob_ok = [](double p) { return p >= 0.0 && p <= 1.0; };  // false for NaN
  if (params_.latency < 1) fail("latency must be >= 1");
  if (params_.max_per_cycle < 1) fail("max_per_cycle must be >= 1");
  if (params_.max_outstanding < 1) fail("max_outstanding must be >= 1");
  if (params_.max_stall_run < 1) fail("max_stall_run must be >= 1");
  if (!prob_ok(params_.req_stall_prob)) fail("req_stall_prob must be in [0, 1]");
  if (!prob_ok(params_.rsp_stall_prob)) fail("rsp_stall_prob must be in [0, 1]");
}

bool MemoryPort::draw(double p) {
  // 53 random bits -> [0, 1); p = 1 always stalls, p = 0 never draws.
  const double u = static_cast<double>(rng_() >> 11) * 0x1.0p-53;
  return u < p;
}

bool MemoryPort::request_ready() const {
  if (req_stalled_ || accepted_now_ >= params_.max_per_cycle) return false;
  if (outstanding_ >= params_.max_outstanding) return false;
  if (params_.rate_requests > 0 && params_.rate_window > 0 &&
      recent_.size() >= params_.rate_requests)
    return false;
  return true;
}

bool MemoryPort::offer_request(uint32_t tag, uint64_t index) {
  if (!request_ready()) {
    refused_now_ = true;
    ++stats_.refused_offers;
    return false;
  }
  uint64_t extra = 0;
  if (params_.max_extra_delay > 0)
    extra = std::uniform_int_distribution<uint64_t>(0, params_.max_extra_delay)(rng_);
  const InFlight f{cycle_ + params_.latency + extra, seq_++, tag, index};
  waiting_.push(f);
  accepted_tags_.push_back(tag);
  ++outstanding_;
  ++accepted_now_;
  if (params_.rate_requests > 0 && params_.rate_window > 0) recent_.push_back(cycle_);
  ++stats_.requests;
  if (outstanding_ > stats_.max_outstanding) stats_.max_outstanding = outstanding_;
  return true;
}

void MemoryPort::take_response() {
  if (!shown_) throw ProtocolError(name_ + ": take_response() with no response shown");
  taken_ = true;
}

void MemoryPort::tick() {
  bool active = !accepted_tags_.empty();
  if (taken_) {
    ++stats_.responses;
    if (shown_->error)
      ++stats_.errors;
    else
      stats_.bytes += response_bytes();
    tags_.erase(shown_->tag);
    --outstanding_;
    shown_.reset();
    active = true;
  }
  // The tag check happens at the edge, so a core may reuse the tag of the response it takes in the
  // same cycle.
  for (uint32_t tag : accepted_tags_) {
    if (params_.unique_tags && !tags_.insert(tag).second)
      throw ProtocolError(name_ + ": request with tag " + std::to_string(tag) + " in cycle " +
                          std::to_string(cycle_) + " while tag " + std::to_string(tag) +
                          " is outstanding");
  }
  if (refused_now_) ++stats_.refused_cycles;
  idle_ = active ? 0 : idle_ + 1;
  ++stats_.cycles;
  ++cycle_;
  begin_cycle();
}

void MemoryPort::begin_cycle() {
  accepted_now_ = 0;
  accepted_tags_.clear();
  refused_now_ = false;
  taken_ = false;
  while (!recent_.empty() && cycle_ - recent_.front() >= params_.rate_window) recent_.pop_front();

  req_stalled_ = false;
  if (params_.req_stall_prob > 0.0) {
    req_stalled_ = req_stall_run_ < params_.max_stall_run && draw(params_.req_stall_prob);
    req_stall_run_ = req_stalled_ ? req_stall_run_ + 1 : 0;
  }

  if (shown_ || waiting_.empty() || waiting_.top().ready_cycle > cycle_) {
    rsp_stall_run_ = 0;
    return;
  }
  if (params_.rsp_stall_prob > 0.0 && rsp_stall_run_ < params_.max_stall_run &&
      draw(params_.rsp_stall_prob)) {
    ++rsp_stall_run_;
    return;
  }
  rsp_stall_run_ = 0;
  const InFlight f = waiting_.top();
  waiting_.pop();
  MemResponse r;
  r.tag = f.tag;
  r.index = f.index;
  r.error = f.index >= count_;
  r.data = record_words(f.index);
  shown_ = std::move(r);
}

std::vector<uint32_t> MemoryPort::record_words(uint64_t index) const {
  std::vector<uint32_t> words(data_words(), 0);
  if (index >= count_) return words;
  // Record index + j fills response bytes j x record_bytes on; the records past the section stay
  // zero.
  for (uint32_t j = 0; j < records_ && j < count_ - index; ++j) {
    const uint8_t* p = bytes_.data() + (index + j) * stride_;
    for (uint32_t b = 0; b < record_bytes_; ++b) {
      const uint32_t k = j * record_bytes_ + b;
      words[k / 4] |= static_cast<uint32_t>(p[b]) << (8 * (k % 4));
    }
  }
  return words;
}

}  // namespace rc::harness
