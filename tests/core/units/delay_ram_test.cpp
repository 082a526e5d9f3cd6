// rc_delay_ram (rtl/core/rc_delay_ram.sv): a fixed delay line in a memory, distributed RAM or block
// RAM by its size (or block RAM when forced). Verilated at both mappings and at their edges, and
// rc_delay_line (rtl/core/rc_delay_line.sv) either way (CMakeLists.txt lists them).
//
// The contract says data_o = data_i as it was Cycles rising edges earlier: after edge j, data_o
// holds the word sampled at edge j - Cycles + 1, from the Cycles-th edge after reset on. Each
// model gets a seeded random word at every edge for 20 times its depth, then runs of a constant
// word and of alternating all-zero and all-one words (every bit toggles), and every output from
// the first defined one on is checked against the words kept here.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "Vdelay_line_c1w8.h"
#include "Vdelay_line_c22w40.h"
#include "Vdelay_line_c22w40b.h"
#include "Vdelay_ram_c100w48.h"
#include "Vdelay_ram_c11w48b.h"
#include "Vdelay_ram_c16w24.h"
#include "Vdelay_ram_c17w24.h"
#include "Vdelay_ram_c17w4.h"
#include "Vdelay_ram_c2w1.h"
#include "Vdelay_ram_c32w8.h"
#include "Vdelay_ram_c3w5b.h"
#include "Vdelay_ram_c63w25.h"
#include "Vdelay_ram_c65w1.h"
#include "fp_cases.hpp"
#include "verilated_tb.hpp"

namespace rc::test {

using rc::harness::get_field;
using rc::harness::put_field;
using rc::harness::VerilatedTb;
namespace {

template <class V>
void run(int width, int cycles, const char* what) {
  VerilatedTb<V> tb;
  std::mt19937_64 rng(0xde1au + static_cast<uint64_t>(width * 1000 + cycles));
  const uint64_t mask = width == 64 ? ~0ull : (1ull << width) - 1;
  put_field(tb->data_i, 0, width, 0);
  tb.reset(2);

  int depth = 1;
  while (depth < cycles) depth *= 2;
  std::vector<uint64_t> words;
  const int n_random = 20 * depth;
  for (int i = 0; i < n_random; ++i) words.push_back(rng() & mask);
  for (int i = 0; i < 2 * depth; ++i) words.push_back(mask & 0x5a5a5a5a5a5a5a5aull);
  for (int i = 0; i < 2 * depth; ++i) words.push_back((i & 1) ? mask : 0);

  uint64_t cases = 0, bad = 0;
  for (size_t j = 0; j < words.size() + static_cast<size_t>(cycles); ++j) {
    put_field(tb->data_i, 0, width, j < words.size() ? words[j] : 0);
    tb.tick();
    // After edge j (0 = the first after reset): the word of edge j - cycles + 1.
    if (j + 1 < static_cast<size_t>(cycles) || j + 1 - cycles >= words.size()) continue;
    const uint64_t want = words[j + 1 - cycles];
    const uint64_t got = get_field(tb->data_o, 0, width);
    ++cases;
    if (got != want) {
      if (bad < 8)
        ADD_FAILURE() << what << ": after edge " << j << " data_o = " << got << ", want " << want
                      << " (the word of edge " << j + 1 - cycles << ")";
      ++bad;
    }
  }
  report_cases(what, cases, bad);
  EXPECT_EQ(bad, 0u) << what;
}

TEST(DelayRam, TwoCyclesOneBit) { run<Vdelay_ram_c2w1>(1, 2, "rc_delay_ram 2 x 1"); }
TEST(DelayRam, SixteenCyclesDistributed) { run<Vdelay_ram_c16w24>(24, 16, "rc_delay_ram 16 x 24"); }
TEST(DelayRam, SeventeenCyclesBlock) { run<Vdelay_ram_c17w24>(24, 17, "rc_delay_ram 17 x 24"); }
TEST(DelayRam, SeventeenCyclesNarrow) { run<Vdelay_ram_c17w4>(4, 17, "rc_delay_ram 17 x 4"); }
TEST(DelayRam, ThirtyTwoCyclesFull) { run<Vdelay_ram_c32w8>(8, 32, "rc_delay_ram 32 x 8"); }
TEST(DelayRam, SixtyThreeCycles) { run<Vdelay_ram_c63w25>(25, 63, "rc_delay_ram 63 x 25"); }
TEST(DelayRam, SixtyFiveCyclesOneBit) { run<Vdelay_ram_c65w1>(1, 65, "rc_delay_ram 65 x 1"); }
TEST(DelayRam, HundredCyclesWide) { run<Vdelay_ram_c100w48>(48, 100, "rc_delay_ram 100 x 48"); }
TEST(DelayRam, ThreeCyclesForcedBlock) {
  run<Vdelay_ram_c3w5b>(5, 3, "rc_delay_ram 3 x 5, ForceBlock");
}
TEST(DelayRam, ElevenCyclesForcedBlock) {
  run<Vdelay_ram_c11w48b>(48, 11, "rc_delay_ram 11 x 48, ForceBlock");
}
TEST(DelayLine, OneCycleShift) { run<Vdelay_line_c1w8>(8, 1, "rc_delay_line 1 x 8"); }
TEST(DelayLine, TwentyTwoCyclesShift) { run<Vdelay_line_c22w40>(40, 22, "rc_delay_line 22 x 40"); }
TEST(DelayLine, TwentyTwoCyclesBlock) {
  run<Vdelay_line_c22w40b>(40, 22, "rc_delay_line 22 x 40, Block");
}

}  // namespace
}  // namespace rc::test
