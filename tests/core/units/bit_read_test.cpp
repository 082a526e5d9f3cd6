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
//
// With index copies (IdxCopies = the groups: N = 512, LoW = 5, sixteen groups of 32, each reading
// its own copy, as the intersection issue does at 128 threads), every copy but the two the
// contract says are read for the index (copy 0 for the group, the group's own copy for the low
// bits) holds a random index, so a group that read another copy fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "Vbit_read_n20.h"
#include "Vbit_read_n4.h"
#include "Vbit_read_n512.h"
#include "Vbit_read_n512c.h"
#include "fp_cases.hpp"
#include "verilated_tb.hpp"

namespace rc::test {

using rc::harness::clear;
using rc::harness::put_bits;
using rc::harness::put_field;
using rc::harness::VerilatedTb;
namespace {

// Write idx into the model's idx_i: every copy the index (copies = 1: a plain index), or, with
// copies = the groups of 2^low_w bits, copy 0's group bits and the group's own copy's low bits the
// index and every other bit random.
template <class Port>
void set_idx(Port& port, int idx, int idx_w, int low_w, int copies, std::mt19937& rng) {
  if (copies == 1) {
    clear(port);
    put_field(port, 0, idx_w, static_cast<uint64_t>(idx));
    return;
  }
  const uint64_t mask = (uint64_t{1} << idx_w) - 1, low_mask = (uint64_t{1} << low_w) - 1;
  const int grp = idx >> low_w;
  for (int c = 0; c < copies; ++c) {
    uint64_t v = rng() & mask;
    if (c == grp) v = (v & ~low_mask) | (static_cast<uint64_t>(idx) & low_mask);
    if (c == 0) v = (v & low_mask) | (static_cast<uint64_t>(idx) & ~low_mask);
    put_field(port, c * idx_w, idx_w, v);
  }
}

template <class V>
void run(int n, int idx_w, const char* what, int low_w = 0, int copies = 1) {
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
  put_bits(tb->bits_i, samples[0].bits);
  set_idx(tb->idx_i, samples[0].idx, idx_w, low_w, copies, rng);
  tb.eval();
  for (size_t s = 0; s < samples.size(); ++s) {
    const Sample& cur = samples[s];
    const bool want = cur.idx < n && cur.bits[static_cast<size_t>(cur.idx)];
    // Right after the edge, the next sample's inputs (or the complement of this one's).
    const Sample& next = samples[(s + 1) % samples.size()];
    tb.tick([&] {
      put_bits(tb->bits_i, next.bits);
      set_idx(tb->idx_i, next.idx, idx_w, low_w, copies, rng);
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
TEST(BitRead, N512Groups32IndexCopies) {
  run<Vbit_read_n512c>(512, 9, "rc_bit_read N=512 LoW=5 IdxCopies=16", 5, 16);
}
TEST(BitRead, N20Groups4Padded) { run<Vbit_read_n20>(20, 5, "rc_bit_read N=20 IdxW=5 LoW=2"); }
TEST(BitRead, N4OneGroup) { run<Vbit_read_n4>(4, 3, "rc_bit_read N=4 IdxW=3 LoW=6"); }

}  // namespace
}  // namespace rc::test
