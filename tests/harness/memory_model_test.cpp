// The harness's memory model (tb/harness/memory_model.hpp) against the image reader: every record
// of every section read back bit for bit, the timing parameters (latency, per-cycle and windowed
// rate limits, outstanding limit), out-of-order returns with every request answered once,
// reproducibility from the seed, out-of-range indices and the statistics; ports answering several
// consecutive records per request (the core's node port: pairs, make_core_ports()).
#include "memory_model.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iostream>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "compiler.hpp"
#include "core_sim.hpp"
#include "image.hpp"
#include "scene.hpp"

namespace {

using rc::harness::MemoryParams;
using rc::harness::MemoryPort;
using rc::harness::MemResponse;
using rc::harness::ProtocolError;
using rc::scene::NumberFormat;
using rc::scene::SceneImage;

constexpr uint64_t kNever = std::numeric_limits<uint64_t>::max();

const uint32_t kSections[] = {
    static_cast<uint32_t>(rc::spec::kImageSectionIdNodes),
    static_cast<uint32_t>(rc::spec::kImageSectionIdLists),
    static_cast<uint32_t>(rc::spec::kImageSectionIdTriangles),
    static_cast<uint32_t>(rc::spec::kImageSectionIdShading),
};

void print_cases(const std::string& what, uint64_t cases, uint64_t mismatches) {
  std::cout << "[cases] " << what << ": " << cases << " cases, " << mismatches << " mismatches\n";
}

SceneImage build_image(const std::string& input, const NumberFormat& format) {
  const rc::scene::Scene scene = rc::scene::load_scene(input, {});
  rc::scene::CompileOptions options;
  options.format = format;
  rc::scene::Compiled compiled = rc::scene::compile_scene(scene, options);
  return SceneImage::from_bytes(std::move(compiled.image), input);
}

const SceneImage& cornell_fp24() {
  static const SceneImage image = build_image("builtin:cornell", NumberFormat::fp24());
  return image;
}

const SceneImage& cornell_fp32() {
  static const SceneImage image = build_image("builtin:cornell", NumberFormat::fp32());
  return image;
}

const SceneImage& spheres_fp24() {
  static const SceneImage image = build_image("builtin:spheres", NumberFormat::fp24());
  return image;
}

// The record as docs/memory-format.md lays it out, rebuilt from the reader's decoded fields (not
// from the section's bytes, which the port copies).
std::vector<uint8_t> expected_bytes(const SceneImage& image, uint32_t id, uint64_t i) {
  std::vector<uint8_t> b;
  const auto put = [&b](uint64_t v, int n) {
    for (int k = 0; k < n; ++k) b.push_back(static_cast<uint8_t>(v >> (8 * k)));
  };
  const int vb = image.value_bytes();
  switch (id) {
    case rc::spec::kImageSectionIdNodes: put(image.node(i).raw, 8); break;
    case rc::spec::kImageSectionIdLists: put(image.list_entry(i), 4); break;
    case rc::spec::kImageSectionIdTriangles:
      for (int k = 0; k < 12; ++k) put(image.triangle_bits(i, k), vb);
      break;
    case rc::spec::kImageSectionIdShading: {
      const rc::scene::ShadingRecord r = image.shading(i);
      put(r.material, 4);
      for (int k = 0; k < 3; ++k) put(r.normal_bits[k], vb);
      put(r.normal_len_bits, vb);
      break;
    }
    default: ADD_FAILURE() << "no expected layout for section " << id;
  }
  return b;
}

// Record byte k bit b = word (8k + b) / 32 bit (8k + b) % 32, one bit at a time.
std::vector<uint32_t> to_words(const std::vector<uint8_t>& bytes) {
  std::vector<uint32_t> w((bytes.size() * 8 + 31) / 32, 0);
  for (size_t k = 0; k < bytes.size(); ++k)
    for (size_t b = 0; b < 8; ++b)
      if ((bytes[k] >> b) & 1u) w[(8 * k + b) / 32] |= uint32_t{1} << ((8 * k + b) % 32);
  return w;
}

using Expect = std::function<std::vector<uint32_t>(uint64_t)>;

// The response for index i of a port with `records` records per response: records i ..
// i + records - 1 one after the other, a record past the section zero, all zero for i >= count.
Expect expect_for(const SceneImage& image, uint32_t id, uint32_t records = 1) {
  const uint64_t count = image.section(id).count;
  const size_t record = expected_bytes(image, id, 0).size();
  return [&image, id, count, record, records](uint64_t i) {
    std::vector<uint8_t> bytes(record * records, 0);
    for (uint64_t j = 0; j < records && i < count && j < count - i; ++j) {
      const std::vector<uint8_t> r = expected_bytes(image, id, i + j);
      std::copy(r.begin(), r.end(), bytes.begin() + static_cast<std::ptrdiff_t>(j * record));
    }
    return to_words(bytes);
  };
}

// ---- A driver standing in for the core
// ------------------------------------------------------------

struct DriverConfig {
  double offer_p = 1.0;           // chance per cycle to raise req_valid (then held until accepted)
  double take_p = 1.0;            // chance per cycle of rsp_ready
  uint32_t offers_per_cycle = 1;  // requests offered per cycle at most
  uint32_t tags = 64;             // the tag space
  uint64_t seed = 99;             // the driver's own randomness
  uint64_t max_cycles = 5'000'000;
};

struct RunResult {
  std::vector<uint64_t> accept_cycle, shown_cycle, taken_cycle;  // per request
  std::vector<uint64_t> delivery_order;                          // request numbers, as taken
  std::vector<uint32_t> accepts_per_cycle;
  std::vector<uint64_t> outstanding_per_cycle;  // at the start of each cycle
  std::vector<uint64_t> trace;                  // one signature per cycle
  uint64_t cycles = 0, refused_cycles = 0, errors = 0, bytes = 0;
  // Mismatches.
  uint64_t unknown_tag = 0, wrong_index = 0, wrong_data = 0, wrong_error = 0, unstable = 0,
           duplicates = 0, unanswered = 0;
  uint64_t mismatches() const {
    return unknown_tag + wrong_index + wrong_data + wrong_error + unstable + duplicates +
           unanswered;
  }
};

RunResult run(MemoryPort& port, const std::vector<uint64_t>& indices, const DriverConfig& cfg,
              const Expect& expect) {
  RunResult r;
  const size_t n = indices.size();
  r.accept_cycle.assign(n, kNever);
  r.shown_cycle.assign(n, kNever);
  r.taken_cycle.assign(n, kNever);
  std::mt19937_64 rng(cfg.seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const auto chance = [&](double p) { return uni(rng) < p; };

  std::vector<uint32_t> free_tags;
  for (uint32_t t = cfg.tags; t-- > 0;) free_tags.push_back(t);
  std::vector<int64_t> owner(cfg.tags, -1);
  size_t next = 0, delivered = 0;
  bool holding = false;   // req_valid raised and not yet accepted
  int64_t held_tag = -1;  // the tag shown and not taken last cycle, or -1
  uint64_t outstanding = 0;

  for (uint64_t cycle = 0; delivered < n && cycle < cfg.max_cycles; ++cycle) {
    r.outstanding_per_cycle.push_back(outstanding);
    const bool ready = port.request_ready();
    const std::optional<MemResponse>& rsp = port.response();
    int64_t shown_tag = -1;  // rsp refers to the port's state: use it before tick()
    if (rsp) {
      shown_tag = rsp->tag;
      if (held_tag >= 0 && held_tag != rsp->tag) ++r.unstable;  // changed before it was taken
      const int64_t k = rsp->tag < cfg.tags ? owner[rsp->tag] : -1;
      if (k < 0) {
        ++r.unknown_tag;
      } else if (r.shown_cycle[k] == kNever) {
        r.shown_cycle[k] = cycle;
        const uint64_t index = indices[k];
        const bool out = index >= port.count();
        if (rsp->index != index) ++r.wrong_index;
        if (rsp->error != out) ++r.wrong_error;
        if (rsp->data != expect(index)) ++r.wrong_data;
      }
    } else if (held_tag >= 0) {
      ++r.unstable;  // rsp_valid dropped before the response was taken
    }

    uint32_t accepted = 0;
    bool refused = false;
    for (uint32_t o = 0; o < cfg.offers_per_cycle && next < n && !free_tags.empty(); ++o) {
      if (!holding && !chance(cfg.offer_p)) break;
      holding = true;
      const uint32_t tag = free_tags.back();
      if (!port.offer_request(tag, indices[next])) {
        refused = true;
        break;
      }
      free_tags.pop_back();
      owner[tag] = static_cast<int64_t>(next);
      r.accept_cycle[next] = cycle;
      ++next;
      ++accepted;
      ++outstanding;
      holding = false;
    }
    const bool take = rsp && chance(cfg.take_p);
    if (take) port.take_response();
    r.accepts_per_cycle.push_back(accepted);
    if (refused) ++r.refused_cycles;
    r.trace.push_back(static_cast<uint64_t>(ready) | uint64_t{accepted} << 1 |
                      static_cast<uint64_t>(shown_tag + 1) << 8 |
                      static_cast<uint64_t>(take) << 40);

    port.tick();
    r.cycles = cycle + 1;
    held_tag = take ? -1 : shown_tag;
    if (take) {
      const auto tag = static_cast<uint32_t>(shown_tag);
      const int64_t k = tag < cfg.tags ? owner[tag] : -1;
      if (k >= 0) {
        if (r.taken_cycle[k] != kNever) ++r.duplicates;
        r.taken_cycle[k] = cycle;
        r.delivery_order.push_back(static_cast<uint64_t>(k));
        if (indices[k] >= port.count())
          ++r.errors;
        else
          r.bytes += port.response_bytes();
        owner[tag] = -1;
        free_tags.push_back(tag);
        --outstanding;
        ++delivered;
      }
    }
  }
  for (size_t k = 0; k < n; ++k)
    if (r.taken_cycle[k] == kNever) ++r.unanswered;
  return r;
}

std::vector<uint64_t> all_indices(uint64_t count) {
  std::vector<uint64_t> v(count);
  for (uint64_t i = 0; i < count; ++i) v[i] = i;
  return v;
}

std::vector<uint64_t> random_indices(uint64_t count, size_t n, double out_of_range, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<uint64_t> in(0, count - 1), out(count, count + 1000);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::vector<uint64_t> v(n);
  for (auto& i : v) i = uni(rng) < out_of_range ? out(rng) : in(rng);
  return v;
}

// Responses taken after a response to a later request: out-of-order returns.
uint64_t out_of_order(const RunResult& r) {
  uint64_t n = 0, latest = 0;
  bool any = false;
  for (uint64_t k : r.delivery_order) {
    if (any && k < latest) ++n;
    latest = any ? std::max(latest, k) : k;
    any = true;
  }
  return n;
}

MemoryParams stalls_on(uint64_t seed) {
  MemoryParams p;
  p.latency = 5;
  p.max_extra_delay = 24;
  p.req_stall_prob = 0.2;
  p.rsp_stall_prob = 0.2;
  p.max_outstanding = 32;
  p.seed = seed;
  return p;
}

// ---- Tests
// ----------------------------------------------------------------------------------------

TEST(MemoryModel, ReadsEveryRecordOfEverySection) {
  struct Image {
    const char* name;
    const SceneImage* image;
    size_t words[4];  // nodes, lists, triangles, shading
  };
  const Image images[] = {{"cornell fp24", &cornell_fp24(), {2, 1, 9, 4}},
                          {"cornell fp32", &cornell_fp32(), {2, 1, 12, 5}},
                          {"spheres fp24", &spheres_fp24(), {2, 1, 9, 4}}};
  for (const Image& im : images) {
    for (bool stalls : {false, true}) {
      uint64_t cases = 0, mismatches = 0;
      std::string counts;
      for (size_t s = 0; s < 4; ++s) {
        const uint32_t id = kSections[s];
        const MemoryParams params = stalls ? stalls_on(11 + s) : MemoryParams{};
        MemoryPort port(*im.image, id, params);
        ASSERT_EQ(port.count(), im.image->section(id).count);
        ASSERT_GT(port.count(), 0u);
        EXPECT_EQ(port.data_words(), im.words[s]) << rc::scene::section_name(id);
        EXPECT_EQ(port.data_words(), to_words(expected_bytes(*im.image, id, 0)).size());
        DriverConfig cfg;
        if (stalls) cfg.take_p = 0.6;
        const RunResult r = run(port, all_indices(port.count()), cfg, expect_for(*im.image, id));
        EXPECT_EQ(r.mismatches(), 0u) << im.name << " " << rc::scene::section_name(id);
        cases += port.count();
        counts += std::string(s ? ", " : " (") + rc::scene::section_name(id) + " " +
                  std::to_string(port.count());
        mismatches += r.mismatches();
        // The functional read agrees too.
        for (uint64_t i = 0; i < port.count(); ++i)
          if (port.record_words(i) != to_words(expected_bytes(*im.image, id, i))) ++mismatches;
      }
      print_cases(std::string("memory port records read back, ") + im.name +
                      (stalls ? ", stalls on" : ", stalls off") + counts + ")",
                  cases, mismatches);
      EXPECT_EQ(mismatches, 0u);
    }
  }
}

TEST(MemoryModel, LatencyIsExactWithoutStalls) {
  const SceneImage& image = cornell_fp24();
  const uint32_t id = kSections[2];
  uint64_t cases = 0, mismatches = 0;
  for (uint32_t latency : {1u, 2u, 3u, 16u, 40u}) {
    for (double offer_p : {1.0, 0.5}) {
      MemoryParams params;
      params.latency = latency;
      MemoryPort port(image, id, params);
      DriverConfig cfg;
      cfg.offer_p = offer_p;
      const std::vector<uint64_t> idx = random_indices(port.count(), 3000, 0.05, latency);
      const RunResult r = run(port, idx, cfg, expect_for(image, id));
      EXPECT_EQ(r.mismatches(), 0u);
      mismatches += r.mismatches();
      for (size_t k = 0; k < idx.size(); ++k) {
        ++cases;
        if (r.shown_cycle[k] - r.accept_cycle[k] != latency) ++mismatches;
        if (r.delivery_order[k] != k) ++mismatches;  // in order without random delays
      }
    }
  }
  print_cases("memory port latency exact without stalls", cases, mismatches);
  EXPECT_EQ(mismatches, 0u);
}

TEST(MemoryModel, RandomDelaysReturnOutOfOrderAndAnswerEveryRequestOnce) {
  const SceneImage& image = cornell_fp24();
  uint64_t cases = 0, mismatches = 0, reordered = 0, early = 0;
  for (size_t s = 0; s < 4; ++s) {
    const uint32_t id = kSections[s];
    MemoryPort port(image, id, stalls_on(100 + s));
    DriverConfig cfg;
    cfg.offer_p = 0.8;
    cfg.take_p = 0.7;
    cfg.tags = 32;
    cfg.seed = 200 + s;
    const std::vector<uint64_t> idx = random_indices(port.count(), 20000, 0.02, s);
    const RunResult r = run(port, idx, cfg, expect_for(image, id));
    EXPECT_EQ(r.mismatches(), 0u) << rc::scene::section_name(id);
    EXPECT_EQ(r.delivery_order.size(), idx.size());
    const uint64_t oo = out_of_order(r);
    EXPECT_GT(oo, idx.size() / 10) << rc::scene::section_name(id);
    for (size_t k = 0; k < idx.size(); ++k)
      if (r.shown_cycle[k] - r.accept_cycle[k] < port.params().latency) ++early;
    cases += idx.size();
    mismatches += r.mismatches();
    reordered += oo;
  }
  std::cout << "[cases] out-of-order responses: " << reordered << " of " << cases << "\n";
  print_cases("memory port random delays, each request answered once with its tag", cases,
              mismatches + early);
  EXPECT_EQ(mismatches, 0u);
  EXPECT_EQ(early, 0u);
}

TEST(MemoryModel, RateLimitsAreHonoured) {
  const SceneImage& image = cornell_fp24();
  struct Limit {
    uint32_t per_cycle, requests, window;
  };
  const Limit limits[] = {{1, 3, 10}, {2, 5, 7}, {1, 1, 4}, {3, 0, 0}, {4, 9, 3}, {2, 2, 1}};
  uint64_t windows = 0, mismatches = 0;
  for (const Limit& l : limits) {
    for (double stall : {0.0, 0.3}) {
      MemoryParams params;
      params.max_per_cycle = l.per_cycle;
      params.rate_requests = l.requests;
      params.rate_window = l.window;
      params.max_outstanding = 1000;
      params.req_stall_prob = stall;
      params.max_extra_delay = stall > 0.0 ? 8 : 0;
      MemoryPort port(image, kSections[0], params);
      DriverConfig cfg;
      cfg.offers_per_cycle = l.per_cycle + 2;  // try to exceed the limit every cycle
      cfg.tags = 1000;
      const std::vector<uint64_t> idx = random_indices(port.count(), 4000, 0.0, l.requests);
      const RunResult r = run(port, idx, cfg, expect_for(image, kSections[0]));
      mismatches += r.mismatches();
      const auto& a = r.accepts_per_cycle;
      uint32_t max_cycle = 0, max_window = 0;
      for (uint32_t x : a) {
        max_cycle = std::max(max_cycle, x);
        if (x > l.per_cycle) ++mismatches;
      }
      if (l.requests > 0) {
        uint32_t sum = 0;
        for (size_t c = 0; c < a.size(); ++c) {
          sum += a[c];
          if (c >= l.window) sum -= a[c - l.window];
          if (c + 1 >= l.window) {
            ++windows;
            max_window = std::max(max_window, sum);
            if (sum > l.requests) ++mismatches;
          }
        }
        // The limit is reached, not just respected.
        EXPECT_EQ(max_window, std::min(l.requests, l.per_cycle * l.window));
      }
      EXPECT_EQ(max_cycle, l.requests > 0 ? std::min(l.per_cycle, l.requests) : l.per_cycle);
      EXPECT_GT(r.refused_cycles, 0u);
    }
  }
  print_cases("memory port rate limit windows", windows, mismatches);
  EXPECT_EQ(mismatches, 0u);
}

TEST(MemoryModel, OutstandingLimitIsHonoured) {
  const SceneImage& image = cornell_fp24();
  uint64_t cycles = 0, mismatches = 0;
  for (uint32_t limit : {1u, 4u, 17u, 64u}) {
    for (bool stalls : {false, true}) {
      MemoryParams params = stalls ? stalls_on(limit) : MemoryParams{};
      params.max_outstanding = limit;
      MemoryPort port(image, kSections[1], params);
      DriverConfig cfg;
      cfg.take_p = 0.15;
      cfg.tags = 256;
      const std::vector<uint64_t> idx = random_indices(port.count(), 3000, 0.01, limit);
      const RunResult r = run(port, idx, cfg, expect_for(image, kSections[1]));
      mismatches += r.mismatches();
      uint64_t most = 0;
      for (size_t c = 0; c < r.outstanding_per_cycle.size(); ++c) {
        // Outstanding after this cycle's acceptances (the take completes at the edge).
        const uint64_t o = r.outstanding_per_cycle[c] + r.accepts_per_cycle[c];
        most = std::max(most, o);
        if (o > limit) ++mismatches;
        ++cycles;
      }
      EXPECT_EQ(most, limit);
      EXPECT_EQ(port.stats().max_outstanding, limit);
    }
  }
  print_cases("memory port outstanding limit, cycles", cycles, mismatches);
  EXPECT_EQ(mismatches, 0u);
}

TEST(MemoryModel, SameSeedSameTraceDifferentSeedsDiffer) {
  const SceneImage& image = cornell_fp24();
  const uint32_t id = kSections[2];
  const std::vector<uint64_t> idx = random_indices(image.section(id).count, 5000, 0.02, 5);
  DriverConfig cfg;
  cfg.offer_p = 0.8;
  cfg.take_p = 0.7;
  const auto trace = [&](uint64_t seed) {
    MemoryPort port(image, id, stalls_on(seed));
    RunResult r = run(port, idx, cfg, expect_for(image, id));
    EXPECT_EQ(r.mismatches(), 0u);
    return r.trace;
  };
  uint64_t cases = 0, mismatches = 0;
  for (uint64_t seed = 1; seed <= 8; ++seed) {
    const auto a = trace(seed), b = trace(seed), c = trace(seed + 1000);
    cases += 2;
    if (a != b) ++mismatches;
    if (a == c) ++mismatches;
  }
  print_cases("memory port traces (same seed equal, other seed differs)", cases, mismatches);
  EXPECT_EQ(mismatches, 0u);
}

TEST(MemoryModel, OutOfRangeIndexGivesErrorAndZeroData) {
  const SceneImage& image = cornell_fp24();
  uint64_t cases = 0, mismatches = 0;
  for (uint32_t id : kSections) {
    MemoryPort port(image, id, {});
    const uint64_t n = port.count();
    const std::vector<uint64_t> idx = {
        n, n + 1, n - 1, 0, uint64_t{1} << 30, uint64_t{1} << 32, kNever, n + 12345};
    const RunResult r = run(port, idx, {}, expect_for(image, id));
    mismatches += r.mismatches();
    for (uint64_t i : idx) {
      const bool out = i >= n;
      const std::vector<uint32_t> w = port.record_words(i);
      if (w.size() != port.data_words()) ++mismatches;
      if (out && std::any_of(w.begin(), w.end(), [](uint32_t x) { return x != 0; })) ++mismatches;
      ++cases;
    }
    EXPECT_EQ(port.stats().errors, 6u);
    EXPECT_EQ(r.errors, 6u);
  }
  print_cases("memory port out-of-range indices", cases, mismatches);
  EXPECT_EQ(mismatches, 0u);
}

TEST(MemoryModel, StatisticsAndWatchdog) {
  const SceneImage& image = cornell_fp24();
  MemoryParams params = stalls_on(3);
  params.rate_requests = 4;
  params.rate_window = 6;
  MemoryPort port(image, kSections[3], params);
  EXPECT_EQ(port.idle_cycles(), 0u);
  for (int i = 0; i < 25; ++i) port.tick();
  EXPECT_EQ(port.idle_cycles(), 25u);
  DriverConfig cfg;
  cfg.take_p = 0.5;
  cfg.offers_per_cycle = 2;
  const std::vector<uint64_t> idx = random_indices(port.count(), 2000, 0.05, 9);
  const RunResult r = run(port, idx, cfg, expect_for(image, kSections[3]));
  EXPECT_EQ(r.mismatches(), 0u);
  const rc::harness::MemoryStats& s = port.stats();
  EXPECT_EQ(s.cycles, r.cycles + 25);
  EXPECT_EQ(s.requests, idx.size());
  EXPECT_EQ(s.responses, idx.size());
  EXPECT_EQ(s.errors, r.errors);
  EXPECT_GT(s.errors, 0u);
  EXPECT_EQ(s.bytes, r.bytes);
  EXPECT_EQ(s.bytes, (idx.size() - r.errors) * port.record_bytes());
  EXPECT_EQ(s.refused_cycles, r.refused_cycles);
  EXPECT_LE(s.max_outstanding, params.max_outstanding);
  EXPECT_EQ(port.outstanding(), 0u);
  std::cout << "[cases] memory port statistics: " << s.requests << " requests, " << s.responses
            << " responses, " << s.bytes << " bytes, " << s.errors << " errors, "
            << s.refused_cycles << " refused cycles, max outstanding " << s.max_outstanding << ", "
            << s.cycles << " cycles\n";
  // The last cycle took the last response.
  EXPECT_EQ(port.idle_cycles(), 0u);
  for (int i = 0; i < 7; ++i) port.tick();
  EXPECT_EQ(port.idle_cycles(), 7u);
  while (!port.request_ready()) port.tick();
  ASSERT_TRUE(port.offer_request(0, 0));
  port.tick();
  EXPECT_EQ(port.idle_cycles(), 0u);
  port.tick();
  EXPECT_EQ(port.idle_cycles(), 1u);
}

TEST(MemoryModel, StallsOfProbabilityOneStillMakeProgress) {
  const SceneImage& image = cornell_fp24();
  uint64_t cases = 0, mismatches = 0;
  for (uint32_t run_limit : {1u, 3u, 8u}) {
    MemoryParams params;
    params.latency = 2;
    params.req_stall_prob = 1.0;
    params.rsp_stall_prob = 1.0;
    params.max_stall_run = run_limit;
    MemoryPort port(image, kSections[0], params);
    const std::vector<uint64_t> idx = random_indices(port.count(), 500, 0.0, 1);
    const RunResult r = run(port, idx, {}, expect_for(image, kSections[0]));
    mismatches += r.mismatches();
    // A stall run of run_limit cycles, then one cycle with req_ready (or rsp_valid) high.
    uint64_t gap = 0, worst = 0;
    for (uint64_t t : r.trace) {
      gap = (t & 1) ? 0 : gap + 1;
      worst = std::max(worst, gap);
    }
    EXPECT_EQ(worst, run_limit);
    cases += idx.size();
  }
  print_cases("memory port with stall probability 1", cases, mismatches);
  EXPECT_EQ(mismatches, 0u);
}

TEST(MemoryModel, ProtocolAndParameterErrors) {
  const SceneImage& image = cornell_fp24();
  MemoryParams params;
  params.latency = 1;
  MemoryPort port(image, kSections[0], params);
  EXPECT_THROW(port.take_response(), ProtocolError);
  ASSERT_TRUE(port.offer_request(7, 1));
  port.tick();
  ASSERT_TRUE(port.response().has_value());
  EXPECT_EQ(port.response()->tag, 7u);
  // Reusing tag 7 in the cycle its response is taken is allowed ...
  ASSERT_TRUE(port.offer_request(7, 2));
  port.take_response();
  port.take_response();                      // twice in one cycle: the same transfer
  EXPECT_TRUE(port.response().has_value());  // still shown until the edge
  port.tick();
  ASSERT_TRUE(port.response().has_value());
  EXPECT_EQ(port.response()->index, 2u);
  EXPECT_EQ(port.stats().responses, 1u);
  // ... while it is outstanding, not.
  ASSERT_TRUE(port.offer_request(7, 3));
  EXPECT_THROW(port.tick(), ProtocolError);

  const auto bad = [&image](const std::function<void(MemoryParams*)>& change) {
    MemoryParams p;
    change(&p);
    return [&image, p] { MemoryPort(image, kSections[0], p); };
  };
  EXPECT_THROW(bad([](MemoryParams* p) { p->latency = 0; })(), std::invalid_argument);
  EXPECT_THROW(bad([](MemoryParams* p) { p->max_per_cycle = 0; })(), std::invalid_argument);
  EXPECT_THROW(bad([](MemoryParams* p) { p->max_outstanding = 0; })(), std::invalid_argument);
  EXPECT_THROW(bad([](MemoryParams* p) { p->max_stall_run = 0; })(), std::invalid_argument);
  EXPECT_THROW(bad([](MemoryParams* p) { p->req_stall_prob = 1.5; })(), std::invalid_argument);
  EXPECT_THROW(bad([](MemoryParams* p) { p->rsp_stall_prob = -0.1; })(), std::invalid_argument);
  EXPECT_THROW(MemoryPort(image, 99, {}), rc::scene::Error);
  EXPECT_THROW(MemoryPort(image, kSections[0], {}, 0), std::invalid_argument);
}

// The core's node port (docs/memory-format.md, "kd nodes"): a request for node i answers record i
// in bits [63:0] and record i + 1 in bits [127:64], zero for the last node; an error exactly when
// i is outside the section; 16 bytes counted per (non-error) response.
TEST(MemoryModel, NodePairResponses) {
  const auto records = static_cast<uint32_t>(rc::spec::kCoreNodeRspRecords);
  ASSERT_EQ(records, 2u);
  const uint32_t id = kSections[0];
  const std::pair<const char*, const SceneImage*> images[] = {{"cornell fp24", &cornell_fp24()},
                                                              {"cornell fp32", &cornell_fp32()},
                                                              {"spheres fp24", &spheres_fp24()}};
  uint64_t cases = 0, mismatches = 0;
  for (const auto& [name, image] : images) {
    for (bool stalls : {false, true}) {
      MemoryPort port(*image, id, stalls ? stalls_on(31) : MemoryParams{}, records);
      const uint64_t n = port.count();
      ASSERT_GT(n, 1u);
      EXPECT_EQ(port.records_per_response(), 2u);
      EXPECT_EQ(port.record_bytes(), 8u);
      EXPECT_EQ(port.response_bytes(), 16u);
      EXPECT_EQ(port.data_words(), 4u);
      // The functional read, against the reader's node words: low half record i, high half
      // record i + 1 or zero.
      for (uint64_t i = 0; i < n; ++i) {
        const std::vector<uint32_t> w = port.record_words(i);
        const uint64_t lo = image->node(i).raw, hi = i + 1 < n ? image->node(i + 1).raw : 0;
        const std::vector<uint32_t> want = {
            static_cast<uint32_t>(lo), static_cast<uint32_t>(lo >> 32), static_cast<uint32_t>(hi),
            static_cast<uint32_t>(hi >> 32)};
        if (w != want) ++mismatches;
        ++cases;
      }
      const std::vector<uint32_t> last = port.record_words(n - 1);
      EXPECT_EQ(last[2], 0u);
      EXPECT_EQ(last[3], 0u);
      EXPECT_NE(last[0] | last[1], 0u) << "a leaf's word has kind 3, never zero";
      // Through the timing model: every node (the last one twice), then indices outside.
      std::vector<uint64_t> idx = all_indices(n);
      idx.push_back(n - 1);
      const std::vector<uint64_t> outside = {n, n + 1, n + 1000, uint64_t{1} << 32, kNever};
      idx.insert(idx.end(), outside.begin(), outside.end());
      DriverConfig cfg;
      if (stalls) cfg.take_p = 0.6;
      const RunResult r = run(port, idx, cfg, expect_for(*image, id, records));
      EXPECT_EQ(r.mismatches(), 0u) << name;
      mismatches += r.mismatches();
      cases += idx.size();
      const rc::harness::MemoryStats& s = port.stats();
      EXPECT_EQ(s.errors, outside.size()) << name;
      EXPECT_EQ(r.errors, outside.size()) << name;
      EXPECT_EQ(s.bytes, 16u * (idx.size() - outside.size())) << name;
      EXPECT_EQ(s.bytes, r.bytes) << name;
      for (uint64_t i : outside) {
        const std::vector<uint32_t> w = port.record_words(i);
        if (w != std::vector<uint32_t>(4, 0)) ++mismatches;
      }
    }
  }
  print_cases("memory port node pairs (record i, record i + 1)", cases, mismatches);
  EXPECT_EQ(mismatches, 0u);
}

// The model is general: any number of records per response, records of any byte count packed
// one after the other across the 32-bit words (here 3 records of 3 bytes: 9 bytes, 3 words).
TEST(MemoryModel, SeveralRecordsPerResponsePackTheirBytes) {
  constexpr uint64_t kCount = 5;
  constexpr uint32_t kStride = 4, kRecord = 3, kRecords = 3;
  std::vector<uint8_t> bytes(kCount * kStride);
  for (size_t k = 0; k < bytes.size(); ++k) bytes[k] = static_cast<uint8_t>(0x11 * (k + 1));
  const Expect expect = [&bytes](uint64_t i) {
    std::vector<uint8_t> b(kRecord * kRecords, 0);
    for (uint64_t j = 0; j < kRecords; ++j)
      for (uint32_t k = 0; k < kRecord; ++k)
        if (i < kCount && i + j < kCount) b[j * kRecord + k] = bytes[(i + j) * kStride + k];
    return to_words(b);
  };
  uint64_t cases = 0, mismatches = 0;
  for (bool stalls : {false, true}) {
    MemoryPort port(bytes, kCount, kStride, kRecord, stalls ? stalls_on(41) : MemoryParams{},
                    "packed", kRecords);
    EXPECT_EQ(port.response_bytes(), 9u);
    EXPECT_EQ(port.data_words(), 3u);
    for (uint64_t i = 0; i < kCount + 3; ++i) {
      if (port.record_words(i) != expect(i)) ++mismatches;
      ++cases;
    }
    // The last record's followers are past the end: zero.
    EXPECT_EQ(port.record_words(kCount - 1)[1], 0u);
    const std::vector<uint64_t> idx = random_indices(kCount, 400, 0.1, 7);
    DriverConfig cfg;
    if (stalls) cfg.take_p = 0.5;
    const RunResult r = run(port, idx, cfg, expect);
    mismatches += r.mismatches();
    cases += idx.size();
    EXPECT_EQ(port.stats().bytes, 9u * (idx.size() - r.errors));
    EXPECT_GT(r.errors, 0u);
  }
  print_cases("memory port, 3 records of 3 bytes per response", cases, mismatches);
  EXPECT_EQ(mismatches, 0u);
  EXPECT_THROW(MemoryPort(bytes, kCount, kStride, kRecord, {}, "none", 0), std::invalid_argument);
}

// The core's five ports: the node port answers pairs, the others single records.
TEST(MemoryModel, CorePortsServeNodePairs) {
  const SceneImage& image = cornell_fp24();
  const auto ports =
      rc::harness::make_core_ports(image, std::array<MemoryParams, rc::harness::kCorePorts>{});
  ASSERT_EQ(ports.size(), static_cast<size_t>(rc::harness::kCorePorts));
  for (int i = 0; i < rc::harness::kCorePorts; ++i) {
    const MemoryPort& p = *ports[static_cast<size_t>(i)];
    const uint32_t want =
        i == rc::harness::kPortNodes ? static_cast<uint32_t>(rc::spec::kCoreNodeRspRecords) : 1u;
    EXPECT_EQ(p.records_per_response(), want) << rc::harness::core_port_name(i);
  }
  const MemoryPort& nodes = *ports[rc::harness::kPortNodes];
  EXPECT_EQ(nodes.response_bytes(), 16u);
  const uint64_t n = nodes.count();
  uint64_t mismatches = 0;
  for (uint64_t i = 0; i < n; ++i)
    if (nodes.record_words(i) != expect_for(image, kSections[0], 2)(i)) ++mismatches;
  EXPECT_EQ(mismatches, 0u);
  // The root record the core gets as configuration is node 0's.
  EXPECT_EQ(rc::harness::root_node_record(image), image.node(0).raw);
}

}  // namespace
