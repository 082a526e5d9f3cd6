// rc_bit_read (rtl/core/rc_bit_read.sv): one bit of a wide vector read by its index through a
// multiplexer split by a register. Verilated at N = 512, LoW = 6 (the core's hit bits at 128
// threads: eight groups of 64), N = 20 with a 5-bit index and LoW = 2 (not a power of two: five
// groups of 4 and three that do not exist, whose indices read 0) and N = 4 with a 3-bit index
// (the hit bits at Threads = 1: one group, LoW larger than the index).
//
// The contract says bit_o, in the cycle after the index, is bits_i[idx_i] as the clock edge
// sampled it. Every index is checked (exhaustive over the index space) against 64 seeded random
// vectors, the one-hot vector of that index and its complement; the vector and the index change
// right after the edge, so a bit_o that followed the inputs instead of the sampled values fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "Vbit_read_n20.h"
#include "Vbit_read_n4.h"
#include "Vbit_read_n512.h"
#include "fp_cases.hpp"
#include "verilated_tb.hpp"

namespace rc::test {

using rc::harness::clear;
using rc::harness::put;
using rc::harness::put_field;
using rc::harness::VerilatedTb;
namespace {

// Write bits into the model's bits_i, whatever type Verilator gave it (an integer or VlWide).
template <class Port>
void set_bits(Port& port, const std::vector<bool>& bits) {
  clear(port);
  for (size_t i = 0; i < bits.size(); ++i)
    if (bits[i]) put_field(port, static_cast<int>(i), 1, 1);
}

template <class V>
void run(int n, int idx_w, const char* what) {
  VerilatedTb<V> tb;
  std::mt19937 rng(0x6b17u + static_cast<uint32_t>(n));
  const int n_idx = 1 << idx_w;

  // The sequence of (vector, index) samples: every index with 66 vectors.
  struct Sample {
    std::vector<bool> bits;
    int idx;
  };
  std::vector<Sample> samples;
  for (int idx = 0; idx < n_idx; ++idx) {
    for (int k = 0; k < 66; ++k) {
      std::vector<bool> bits(static_cast<size_t>(n));
      for (int i = 0; i < n; ++i) {
        if (k == 0)
          bits[i] = (i == idx);  // one-hot
        else if (k == 1)
          bits[i] = (i != idx);  // its complement
        else
          bits[i] = (rng() & 1u) != 0;
      }
      samples.push_back({std::move(bits), idx});
    }
  }
  std::shuffle(samples.begin(), samples.end(), rng);

  uint64_t cases = 0, bad = 0;
  set_bits(tb->bits_i, samples[0].bits);
  put(tb->idx_i, static_cast<uint64_t>(samples[0].idx));
  tb.eval();
  for (size_t s = 0; s < samples.size(); ++s) {
    const Sample& cur = samples[s];
    const bool want = cur.idx < n && cur.bits[static_cast<size_t>(cur.idx)];
    // Right after the edge, the next sample's inputs (or the complement of this one's).
    const Sample& next = samples[(s + 1) % samples.size()];
    tb.tick([&] {
      set_bits(tb->bits_i, next.bits);
      put(tb->idx_i, static_cast<uint64_t>(next.idx));
    });
    ++cases;
    if (static_cast<bool>(tb->bit_o) != want) {
      if (bad < 8)
        ADD_FAILURE() << what << ": index " << cur.idx << " gave " << int(tb->bit_o) << ", want "
                      << want;
      ++bad;
    }
  }
  report_cases(what, cases, bad);
  EXPECT_EQ(bad, 0u) << what;
}

TEST(BitRead, N512Groups64) { run<Vbit_read_n512>(512, 9, "rc_bit_read N=512 LoW=6"); }
TEST(BitRead, N20Groups4Padded) { run<Vbit_read_n20>(20, 5, "rc_bit_read N=20 IdxW=5 LoW=2"); }
TEST(BitRead, N4OneGroup) { run<Vbit_read_n4>(4, 3, "rc_bit_read N=4 IdxW=3 LoW=6"); }

}  // namespace
}  // namespace rc::test
