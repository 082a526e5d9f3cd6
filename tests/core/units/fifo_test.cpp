// rc_fifo (rtl/core/rc_fifo.sv, around rc_credit_fifo): a queue whose writer checks count_o before
// it pushes. Verilated with 16-bit entries at Depth 1 (the head register alone, no storage behind
// it: the tracer's tree packet queue), 2 and 5, each with the entries behind the head in flip-flops
// (MemArray 0) and in distributed RAM (MemArray 1).
//
// The contract, as a model: a deque. Before every edge valid_o = the deque is not empty, data_o =
// its front and count_o = its size; at the edge, valid_o & ready_i pops the front and push_i
// appends data_i. Seeded random pushes (only while the size is below Depth, as the contract asks:
// a push into a full queue is illegal, even with a pop in the same cycle) and random ready_i, in
// three phases: pushes more likely than pops (the queue mostly full), equally likely, and pops
// more likely (mostly empty). The model's own assertions (Verilator --assert) fail the test too.
#include <gtest/gtest.h>

#include <cstdint>
#include <deque>
#include <random>

#include "Vfifo_d1.h"
#include "Vfifo_d1m.h"
#include "Vfifo_d2.h"
#include "Vfifo_d2m.h"
#include "Vfifo_d5.h"
#include "Vfifo_d5m.h"
#include "fp_cases.hpp"
#include "verilated_tb.hpp"

namespace rc::test {

using rc::harness::VerilatedTb;
namespace {

template <class V>
void run(unsigned depth, const char* what) {
  VerilatedTb<V> tb;
  std::mt19937 rng(0xf1f0u + depth);
  std::deque<uint32_t> model;

  tb->push_i = 0;
  tb->data_i = 0;
  tb->ready_i = 0;
  tb.reset(2);

  uint64_t cases = 0, bad = 0, pushes = 0, pops = 0, full = 0, empty = 0;
  bool push = false, ready = false;  // the inputs the next edge samples
  uint32_t data = 0;
  int phase = 0;
  const unsigned push_pct[3] = {80, 50, 20};
  const unsigned ready_pct[3] = {30, 50, 85};
  // Right after each edge: the model takes that edge's handshakes, the outputs (registers) are
  // compared with it, and the next edge's inputs are set (tick()'s at_edge).
  const auto at_edge = [&] {
    if (model.empty() ? false : ready) {
      model.pop_front();
      ++pops;
    }
    if (push) {
      model.push_back(data);
      ++pushes;
    }
    const bool want_valid = !model.empty();
    full += model.size() == depth;
    empty += model.empty();
    const bool ok = tb->valid_o == want_valid && tb->count_o == model.size() &&
                    (!want_valid || tb->data_o == model.front());
    ++cases;
    if (!ok && ++bad <= 5)
      ADD_FAILURE() << what << " cycle " << tb.cycles() << ": valid " << int(tb->valid_o)
                    << " count " << int(tb->count_o) << " data " << tb->data_o
                    << ", expected valid " << want_valid << " count " << model.size() << " data "
                    << (want_valid ? model.front() : 0u);
    push = model.size() < depth && rng() % 100u < push_pct[phase];
    ready = rng() % 100u < ready_pct[phase];
    data = rng() & 0xffffu;
    tb->push_i = push;
    tb->data_i = static_cast<uint16_t>(data);
    tb->ready_i = ready;
  };
  for (phase = 0; phase < 3; ++phase) {
    for (int c = 0; c < 4000; ++c) tb.tick(at_edge);
  }
  // Both ends were busy: thousands of pushes and pops, and the queue full and empty many times.
  EXPECT_GT(pushes, 2000u) << what;
  EXPECT_GT(pops, 2000u) << what;
  EXPECT_GT(full, 1000u) << what;
  EXPECT_GT(empty, 1000u) << what;
  report_cases(what, cases, bad);
  EXPECT_EQ(bad, 0u) << what;
}

}  // namespace

TEST(Fifo, Depth1Flat) { run<Vfifo_d1>(1, "rc_fifo Depth 1, flip-flops"); }
TEST(Fifo, Depth1Mem) { run<Vfifo_d1m>(1, "rc_fifo Depth 1, distributed RAM"); }
TEST(Fifo, Depth2Flat) { run<Vfifo_d2>(2, "rc_fifo Depth 2, flip-flops"); }
TEST(Fifo, Depth2Mem) { run<Vfifo_d2m>(2, "rc_fifo Depth 2, distributed RAM"); }
TEST(Fifo, Depth5Flat) { run<Vfifo_d5>(5, "rc_fifo Depth 5, flip-flops"); }
TEST(Fifo, Depth5Mem) { run<Vfifo_d5m>(5, "rc_fifo Depth 5, distributed RAM"); }

}  // namespace rc::test
