// The harness's memory model: one read port of the core's memory interface, serving one section of
// a memory image by record index (docs/architecture.md, "Memory ports"; record layouts in
// docs/memory-format.md). It is plain C++, cycle based and independent of the RTL: the harness
// copies its outputs onto the verilated port's inputs and reports the port's handshakes back.
//
// Records per response: a port answers a request for index i with `records_per_response` (n >= 1)
// consecutive records, i .. i + n - 1, one after the other in the response data (record i + j
// from byte j x record_bytes on). A record past the end of the section is delivered as zeros;
// the response is an error (and all zero) exactly when i itself is outside the section. The
// core's node port reads pairs (n = spec::kCoreNodeRspRecords = 2: record i in bits [63:0],
// record i + 1 in [127:64], so one read brings both children of an inner node); every other
// port reads single records (n = 1).
//
// One clock cycle, as the harness drives it:
//
//   // before evaluating the core: the port's outputs for this cycle
//   port.request_ready()   -> req_ready
//   port.response()        -> rsp_valid (has_value()), rsp_tag, rsp_data, rsp_error
//   // after evaluating the core: the handshakes that complete at the coming edge
//   if (req_valid) port.offer_request(req_tag, req_index);   // accepted iff it returns true
//   if (rsp_valid && rsp_ready) port.take_response();
//   port.tick();            // the clock edge
//
// The port's outputs for a cycle are fixed when the cycle starts (at tick() or construction) and do
// not depend on the consumer's inputs in that cycle, so the model adds no combinational path. A
// response, once shown, stays shown with the same contents until it is taken.
//
// Timing: a request accepted in cycle c has its response ready in cycle c + latency + extra, where
// extra is drawn uniformly from 0 .. max_extra_delay. The port shows one response per cycle; among
// the ready ones it shows the one that became ready first (ties: the one accepted first), so with
// extra delays the responses come back out of order. With no random delays and a consumer that
// takes every response at once, every response is shown exactly `latency` cycles after its request
// was accepted.
//
// Never deadlocks: every response becomes ready after a finite delay, random withholding of
// rsp_valid and random stalls of req_ready last at most max_stall_run cycles in a row, and an
// outstanding request (accepted, its response not yet taken) leaves as soon as its response is
// taken. So while the consumer takes responses, every request is answered exactly once.
//
// Randomness: one std::mt19937_64 seeded from MemoryParams::seed; given the same parameters and the
// same calls, a run is reproducible cycle by cycle.
#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <queue>
#include <random>
#include <stdexcept>
#include <string>
#include <unordered_set>
#include <vector>

#include "image.hpp"

namespace rc::harness {

struct MemoryParams {
  // Cycles from the cycle a request is accepted to the cycle its response is first shown (>= 1).
  uint32_t latency = 16;
  // Requests accepted per cycle (>= 1); a port with one req_valid uses 1.
  uint32_t max_per_cycle = 1;
  // Rate limit: at most rate_requests accepted in any rate_window consecutive cycles (a sliding
  // window). 0 in either field: unlimited.
  uint32_t rate_requests = 0;
  uint32_t rate_window = 0;
  // Accepted requests whose responses have not been taken yet; req_ready is low while full (>= 1).
  uint32_t max_outstanding = 64;
  // Seeded random stalls (all 0: none).
  double req_stall_prob = 0.0;   // per cycle: req_ready low
  uint32_t max_extra_delay = 0;  // per request: 0 .. max_extra_delay extra cycles of latency
  double rsp_stall_prob = 0.0;   // per cycle: a ready response is not shown (rsp_valid withheld)
  // Random stalls of either kind last at most this many cycles in a row (>= 1).
  uint32_t max_stall_run = 8;
  // Protocol check: offering a tag that is still outstanding throws ProtocolError.
  bool unique_tags = true;
  uint64_t seed = 1;
};

struct MemoryStats {
  uint64_t cycles = 0;     // tick() calls
  uint64_t requests = 0;   // requests accepted
  uint64_t responses = 0;  // responses taken (error responses included)
  // Response bytes delivered: response_bytes() per non-error response taken, the zeros standing
  // for records past the section included (they are on the port all the same); error responses
  // deliver none.
  uint64_t bytes = 0;
  uint64_t refused_cycles = 0;   // cycles in which at least one offered request was refused
  uint64_t refused_offers = 0;   // offer_request() calls that returned false
  uint64_t max_outstanding = 0;  // the most outstanding requests at any time
  uint64_t errors = 0;           // error responses taken (index out of range)
};

struct MemResponse {
  uint32_t tag = 0;
  uint64_t index = 0;  // the request's index (for diagnostics; not a port signal)
  bool error = false;  // index >= count: data is all zero
  // The response's records (record_words(index)), little-endian: response byte k (byte
  // k % record_bytes of record index + k / record_bytes) bit b is data[(8k + b) / 32] bit
  // (8k + b) % 32. The bits above the response's last byte are zero.
  std::vector<uint32_t> data;
};

// A misuse of the port by the harness or the core: take_response() with no response shown, or a
// tag offered while a request with the same tag is outstanding (with MemoryParams::unique_tags).
class ProtocolError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

class MemoryPort {
 public:
  // Serves section `section_id` of `image` (spec::kImageSectionIdNodes, ...Lists, ...Triangles,
  // ...Shading; any other section of the image works too, a record being its whole stride),
  // `records_per_response` records per response (see the top of this file). The section's bytes
  // are copied; the image need not outlive the port. Record widths: nodes 8 bytes, lists 4,
  // triangles 12 x value_bytes, shading 4 + 4 x value_bytes (the stride's zero padding is not
  // delivered). Throws std::invalid_argument for bad parameters (records_per_response 0 too),
  // rc::scene::Error for a missing section.
  MemoryPort(const scene::SceneImage& image, uint32_t section_id, const MemoryParams& params = {},
             uint32_t records_per_response = 1);
  // A section given directly: count records of `stride` bytes, of which the first record_bytes are
  // delivered.
  MemoryPort(std::vector<uint8_t> section_bytes, uint64_t count, uint32_t stride,
             uint32_t record_bytes, const MemoryParams& params = {}, std::string name = "memory",
             uint32_t records_per_response = 1);

  // ---- One cycle (see the top of this file) ----

  // req_ready this cycle: whether offer_request() would accept a request now.
  bool request_ready() const;
  // Offers one request (req_valid with req_tag, req_index); returns whether it was accepted (the
  // request handshake completes at the coming edge). May be called up to max_per_cycle times per
  // cycle. Throws ProtocolError for a duplicate outstanding tag.
  bool offer_request(uint32_t tag, uint64_t index);
  // The response shown this cycle (rsp_valid = has_value()); unchanged until taken. The reference
  // stays valid until the next take_response() or tick().
  const std::optional<MemResponse>& response() const { return shown_; }
  // rsp_ready was 1 while a response was shown: it is delivered at the coming edge (and still shown
  // until tick()). Calling it again in the same cycle changes nothing. Throws ProtocolError when no
  // response is shown.
  void take_response();
  // The clock edge: completes this cycle's transfers and sets up the next cycle's outputs.
  void tick();

  // ---- State and statistics ----

  uint64_t cycle() const { return cycle_; }  // the current cycle, 0 after construction
  size_t outstanding() const { return outstanding_; }
  const MemoryStats& stats() const { return stats_; }
  // Watchdog: cycles since a request was last accepted or a response last taken (or since
  // construction). A harness may call the core hung when this grows large while outstanding() > 0
  // or while the core still has work.
  uint64_t idle_cycles() const { return idle_; }

  const MemoryParams& params() const { return params_; }
  const std::string& name() const { return name_; }
  uint64_t count() const { return count_; }                // records in the section
  uint32_t record_bytes() const { return record_bytes_; }  // bytes delivered per record
  uint32_t records_per_response() const { return records_; }
  // Bytes of one response's data: records_per_response() x record_bytes().
  uint32_t response_bytes() const { return records_ * record_bytes_; }
  size_t data_words() const { return (response_bytes() + 3) / 4; }  // rsp_data words
  // The response data for a request for `index` as rsp_data words, without any timing: records
  // index .. index + records_per_response() - 1 (zeros past the section), all zero when
  // index >= count. It is also the line `index` of the board build's ROM for this port
  // (rc_board_rom).
  std::vector<uint32_t> record_words(uint64_t index) const;

 private:
  struct InFlight {
    uint64_t ready_cycle;  // first cycle in which the response may be shown
    uint64_t seq;          // acceptance order
    uint32_t tag;
    uint64_t index;
  };
  struct Later {
    bool operator()(const InFlight& a, const InFlight& b) const {
      return a.ready_cycle != b.ready_cycle ? a.ready_cycle > b.ready_cycle : a.seq > b.seq;
    }
  };

  void check_params() const;
  bool draw(double p);
  void begin_cycle();

  MemoryParams params_;
  std::string name_;
  std::vector<uint8_t> bytes_;
  uint64_t count_ = 0;
  uint32_t stride_ = 0;
  uint32_t record_bytes_ = 0;
  uint32_t records_ = 1;  // records per response
  std::mt19937_64 rng_;

  uint64_t cycle_ = 0;
  uint64_t seq_ = 0;
  uint64_t idle_ = 0;
  size_t outstanding_ = 0;
  std::priority_queue<InFlight, std::vector<InFlight>, Later> waiting_;  // not yet shown
  std::unordered_set<uint32_t> tags_;                                    // outstanding tags
  std::vector<uint32_t> accepted_tags_;                                  // tags accepted this cycle
  std::deque<uint64_t> recent_;  // acceptance cycles inside the rate window
  std::optional<MemResponse> shown_;
  bool taken_ = false;
  bool req_stalled_ = false;
  uint32_t accepted_now_ = 0;
  bool refused_now_ = false;
  uint32_t req_stall_run_ = 0;
  uint32_t rsp_stall_run_ = 0;
  MemoryStats stats_;
};

}  // namespace rc::harness
