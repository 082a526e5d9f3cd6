// rc_rr_pick (rtl/core/rc_rr_pick.sv), the core's round-robin thread scheduler, verilated at
// N = 16 (the default thread count), 5 (not a power of two) and 1, exhaustively: for every pointer
// value and every request vector, valid_o and idx_o against a plain scan (the first requester at
// or after the pointer, wrapping around); then seeded random takes, checking after each that the
// pointer moved to the taken index + 1 (mod N) by the choice it makes next; one take in eight has
// no request at all, which must return the pointer to 0. grant_o (the choice one-hot) is checked
// against the same reference in every case.
#include <gtest/gtest.h>

#include <cstdint>
#include <memory>
#include <random>
#include <type_traits>

#include "Vrr_pick_n1.h"
#include "Vrr_pick_n16.h"
#include "Vrr_pick_n5.h"
#include "fp_cases.hpp"
#include "verilated.h"

namespace rc::test {
namespace {

// The reference: the first set bit of req at or after ptr, wrapping; -1 when req is 0.
int first_from(uint32_t req, int ptr, int n) {
  for (int i = 0; i < n; ++i) {
    const int j = (ptr + i) % n;
    if ((req >> j) & 1u) return j;
  }
  return -1;
}

template <class V>
class Picker {
 public:
  explicit Picker(int n) : n_(n) {
    ctx_ = std::make_unique<VerilatedContext>();
    ctx_->assertOn(true);
    m_ = std::make_unique<V>(ctx_.get());
    m_->clk_i = 0;
    m_->rst_ni = 0;
    m_->req_i = 0;
    m_->take_i = 0;
    m_->eval();
    m_->rst_ni = 1;
    m_->eval();
    for (int i = 0; i < 4; ++i) tick();
  }
  ~Picker() { m_->final(); }
  Picker(const Picker&) = delete;
  Picker& operator=(const Picker&) = delete;

  void tick() {
    m_->clk_i = 1;
    m_->eval();
    m_->clk_i = 0;
    m_->eval();
  }
  // The choice for req with no take (combinational): the index, or -1 when valid_o is 0.
  int choose(uint32_t req) {
    m_->req_i = static_cast<std::remove_reference_t<decltype(m_->req_i)>>(req);
    m_->take_i = 0;
    m_->eval();
    grant_ = static_cast<uint32_t>(m_->grant_o);
    return m_->valid_o ? static_cast<int>(m_->idx_o) : -1;
  }
  // grant_o at the last choice.
  uint32_t grant() const { return grant_; }
  // Take the current choice for req; returns it (-1 with no request).
  int take(uint32_t req) {
    const int got = choose(req);
    m_->take_i = 1;
    m_->eval();
    tick();
    m_->take_i = 0;
    m_->req_i = 0;
    m_->eval();
    return got;
  }
  // Move the pointer to p: take requester (p - 1) mod N alone.
  void set_ptr(int p) { take(1u << ((p + n_ - 1) % n_)); }

 private:
  int n_;
  uint32_t grant_ = 0;
  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<V> m_;
};

template <class V>
void run(int n, const char* what) {
  Picker<V> pk(n);
  uint64_t cases = 0, bad = 0;
  const uint32_t all = n >= 32 ? 0xffffffffu : (1u << n) - 1u;
  for (int p = 0; p < n; ++p) {
    pk.set_ptr(p);
    for (uint32_t req = 0; req <= all; ++req) {
      const int want = first_from(req, p, n);
      const int got = pk.choose(req);
      const uint32_t want_grant = want < 0 ? 0u : 1u << want;
      ++cases;
      if (got != want || pk.grant() != want_grant) {
        if (bad < 8)
          ADD_FAILURE() << what << ": ptr " << p << " req 0x" << std::hex << req << std::dec
                        << ": idx " << got << ", want " << want << ", grant 0x" << std::hex
                        << pk.grant() << std::dec;
        ++bad;
      }
      if (req == all) break;
    }
  }
  // Random takes: the pointer follows the taken index, observed through the next choice with all
  // requesters asking (which must then be taken index + 1 mod N, or 0 after a take without a
  // request).
  std::mt19937 rng(0x5eed0000u + static_cast<uint32_t>(n));
  int ptr = 0;
  pk.set_ptr(0);
  for (int k = 0; k < 20000; ++k) {
    const uint32_t r = static_cast<uint32_t>(rng());
    const bool none = (r >> 29) == 0u;
    const uint32_t req =
        none ? 0u : (r & all) | (1u << (static_cast<uint32_t>(rng()) % static_cast<uint32_t>(n)));
    const int want = first_from(req, ptr, n);
    const int got = pk.take(req);
    ++cases;
    if (got != want) {
      if (bad < 8) ADD_FAILURE() << what << ": take " << k << ": idx " << got << ", want " << want;
      ++bad;
    }
    ptr = none ? 0 : (want + 1) % n;
    ++cases;
    if (pk.choose(all) != ptr) {
      if (bad < 8) ADD_FAILURE() << what << ": take " << k << ": pointer not at " << ptr;
      ++bad;
    }
  }
  report_cases(what, cases, bad);
  EXPECT_EQ(bad, 0u);
}

TEST(RrPick, N16Exhaustive) {
  run<Vrr_pick_n16>(16, "rc_rr_pick N=16 (every pointer, every request)");
}
TEST(RrPick, N5Exhaustive) { run<Vrr_pick_n5>(5, "rc_rr_pick N=5 (every pointer, every request)"); }
TEST(RrPick, N1Exhaustive) { run<Vrr_pick_n1>(1, "rc_rr_pick N=1 (every pointer, every request)"); }

}  // namespace
}  // namespace rc::test
