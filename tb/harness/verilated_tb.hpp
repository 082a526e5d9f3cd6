// The one wrapper of a Verilated model (after ZipCPU's testb.h), used by the harness (the core's
// and the board's runs) and by every test bench: it owns the VerilatedContext and the model, and
// does reset, the clock, the cycle count, the waveform and the error checks; beside it, the helpers
// that read and write ports of any width. Header-only, Verilator's public API only (no
// Verilator-internal names).
//
// Contract
// - VerilatedTb<V> needs ports clk_i and (for reset() only) rst_ni on V. The constructor makes
//   the context (assertions on; fatalOnError as asked: Verilator's default true aborts the process
//   at a failing RTL assertion, false leaves it to check()), passes `args` (argv[0] first) for
//   $value$plusargs, turns tracing on when asked (`trace`: needed before the model exists for
//   open_trace()), makes the model with instance name `name` and sets clk_i = 0. The destructor
//   closes the waveform, then calls the model's final().
// - reset(n, tick_fn): clk_i = 0, rst_ni = 0, eval; n cycles of tick_fn (the bench's own cycle,
//   default tick(), so its per-cycle work runs through reset too); rst_ni = 1, eval. The bench
//   sets its other inputs before.
// - tick(at_edge): one clock cycle from clk_i = 0: clk_i = 1, eval (the rising edge), at_edge()
//   (default none: outputs right after the edge, inputs for the next cycle), clk_i = 0, eval; the
//   simulation time advances by 1 at each half; cycles() + 1; then check(). Inputs for the edge
//   are set (and, to sample combinational outputs before it, eval() called) by the bench before.
// - cycles(): rising edges since construction, those of reset() included.
// - check(): an RTL error ($error, failed assertion, $stop: VerilatedContext::gotError) or
//   $finish (gotFinish) throws TbError naming the model and the cycle; GoogleTest reports it as a
//   failure of the test. Called by tick(); a bench may call it after its own eval().
// - Waveform: open_trace(path, levels) opens an FST file of the model (the constructor's `trace`
//   must have been true; the caller includes verilated_fst_c.h and links Verilator's FST
//   runtime; TbError if the file cannot be opened); dump(time) writes the signals at the bench's
//   time stamp (nothing before open_trace()); flush_trace() flushes. Benches without a waveform
//   need neither the header nor the runtime.
// - Ports: clear(p), put_field(p, lsb, width, v) and get_field(p, lsb, width) take an integer
//   port (CData, SData, IData, QData) or a VlWide<N>; width <= 64; bit i of a VlWide is bit
//   i % 32 of word i / 32 (element i of a [N][W] packed array sits at bits [i*W +: W]);
//   put_field changes only its field. put(p, v) assigns v to an integer port (truncated).
//   put_bits(p, bits) sets bit i of a port of any width to bits[i] and clears the rest.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "verilated.h"

class VerilatedFstC;  // verilated_fst_c.h, needed only by the benches that call open_trace()

namespace rc::harness {

// A Verilated model reported an error or $finish.
class TbError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

template <class V>
class VerilatedTb {
 public:
  explicit VerilatedTb(const char* name = "TOP", bool fatal_on_error = true,
                       const std::vector<std::string>& args = {}, bool trace = false)
      : name_(name), ctx_(std::make_unique<VerilatedContext>()) {
    ctx_->assertOn(true);
    ctx_->fatalOnError(fatal_on_error);
    if (!args.empty()) {
      std::vector<const char*> argv;
      for (const std::string& a : args) argv.push_back(a.c_str());
      ctx_->commandArgs(static_cast<int>(argv.size()), argv.data());
    }
    if (trace) ctx_->traceEverOn(true);
    m_ = std::make_unique<V>(ctx_.get(), name);
    m_->clk_i = 0;
  }
  ~VerilatedTb() {
    dump_ = nullptr;
    flush_ = nullptr;
    trace_.reset();  // closes the file
    m_->final();
  }
  VerilatedTb(const VerilatedTb&) = delete;
  VerilatedTb& operator=(const VerilatedTb&) = delete;

  V& m() { return *m_; }
  const V& m() const { return *m_; }
  V* operator->() { return m_.get(); }
  VerilatedContext& ctx() { return *ctx_; }
  uint64_t cycles() const { return cycles_; }
  void eval() { m_->eval(); }

  template <class F>
  void tick(F&& at_edge) {
    m_->clk_i = 1;
    m_->eval();
    ctx_->timeInc(1);
    at_edge();
    m_->clk_i = 0;
    m_->eval();
    ctx_->timeInc(1);
    ++cycles_;
    check();
  }
  void tick() {
    tick([] {});
  }

  template <class F>
  void reset(int n, F&& tick_fn) {
    m_->clk_i = 0;
    m_->rst_ni = 0;
    m_->eval();
    for (int i = 0; i < n; ++i) tick_fn();
    m_->rst_ni = 1;
    m_->eval();
  }
  void reset(int n) {
    reset(n, [this] { tick(); });
  }

  // The waveform (a function template, so that only its callers need the FST runtime).
  template <class Fst = VerilatedFstC>
  void open_trace(const std::string& path, int levels = 99) {
    std::shared_ptr<Fst> f(new Fst, [](Fst* p) {
      p->close();
      delete p;
    });
    m_->trace(f.get(), levels);
    f->open(path.c_str());
    if (!f->isOpen()) throw TbError(path + ": cannot open the waveform file");
    Fst* raw = f.get();  // trace_ alone owns the file, so the destructor closes it first
    dump_ = [raw](uint64_t time) { raw->dump(time); };
    flush_ = [raw] { raw->flush(); };
    trace_ = f;
  }
  bool tracing() const { return trace_ != nullptr; }
  void dump(uint64_t time) {
    if (dump_) dump_(time);
  }
  void flush_trace() {
    if (flush_) flush_();
  }

  void check() const {
    if (ctx_->gotError())
      throw TbError(name_ + ": an RTL error (failed assertion, $error or $stop; its %Error line " +
                    "is above) at cycle " + std::to_string(cycles_));
    if (ctx_->gotFinish()) throw TbError(name_ + ": $finish at cycle " + std::to_string(cycles_));
  }

 private:
  std::string name_;
  std::unique_ptr<VerilatedContext> ctx_;  // outlives the model
  std::unique_ptr<V> m_;
  std::shared_ptr<void> trace_;  // the open waveform, if any (its deleter closes the file)
  std::function<void(uint64_t)> dump_;
  std::function<void()> flush_;
  uint64_t cycles_ = 0;
};

// ---- Ports of any width ----

// A field's mask, width 0..64.
inline uint64_t field_mask(int width) {
  return width >= 64 ? ~uint64_t{0} : (uint64_t{1} << width) - 1;
}

template <class P, std::enable_if_t<std::is_integral_v<P>, int> = 0>
void clear(P& port) {
  port = 0;
}
template <std::size_t N>
void clear(VlWide<N>& port) {
  for (std::size_t i = 0; i < N; ++i) port[i] = 0;
}

template <class P, std::enable_if_t<std::is_integral_v<P>, int> = 0>
void put_field(P& port, int lsb, int width, uint64_t value) {
  const uint64_t m = field_mask(width) << lsb;
  port = static_cast<P>((static_cast<uint64_t>(port) & ~m) | ((value << lsb) & m));
}
template <std::size_t N>
void put_field(VlWide<N>& port, int lsb, int width, uint64_t value) {
  for (int i = 0; i < width;) {
    const int bit = lsb + i, off = bit % 32, n = std::min(32 - off, width - i);
    const uint32_t m = static_cast<uint32_t>(field_mask(n)) << off;
    const uint32_t v = static_cast<uint32_t>(value >> i) << off;
    port[bit / 32] = (port[bit / 32] & ~m) | (v & m);
    i += n;
  }
}

template <class P>
void put_bits(P& port, const std::vector<bool>& bits) {
  clear(port);
  for (std::size_t i = 0; i < bits.size(); ++i)
    if (bits[i]) put_field(port, static_cast<int>(i), 1, 1);
}

template <class P, std::enable_if_t<std::is_integral_v<P>, int> = 0>
uint64_t get_field(const P& port, int lsb, int width) {
  return (static_cast<uint64_t>(port) >> lsb) & field_mask(width);
}
template <std::size_t N>
uint64_t get_field(const VlWide<N>& port, int lsb, int width) {
  uint64_t v = 0;
  for (int i = 0; i < width;) {
    const int bit = lsb + i, off = bit % 32, n = std::min(32 - off, width - i);
    v |= ((static_cast<uint64_t>(port[bit / 32]) >> off) & field_mask(n)) << i;
    i += n;
  }
  return v;
}

// An integer port set to value (truncated to the port's C type, as an assignment).
template <class P, std::enable_if_t<std::is_integral_v<P>, int> = 0>
void put(P& port, uint64_t value) {
  port = static_cast<P>(value);
}

}  // namespace rc::harness
