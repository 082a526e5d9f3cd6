// The definition of rc::harness::CoreSim<Model> (core_sim.hpp). Included by core_sim.cpp for the
// build's core models, and by tests that instantiate the harness for a model of their own (a
// fake core with rc_core's ports). Needs the model's header and Verilator's runtime.
#pragma once

#include <verilated.h>
#include <verilated_fst_c.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <random>
#include <sstream>
#include <type_traits>
#include <utility>

#include "core_sim.hpp"
#include "error.hpp"
#include "geometry.hpp"
#include "verilated_tb.hpp"

namespace rc::harness {

namespace detail {

// A memory response's data words (little-endian 32-bit words) onto a data port.
template <class P>
void set_words(P& port, const std::vector<uint32_t>& words) {
  static_assert(std::is_integral<P>::value, "scalar port");
  uint64_t v = 0;
  for (size_t i = 0; i < words.size() && i < 2; ++i)
    v |= static_cast<uint64_t>(words[i]) << (32 * i);
  port = static_cast<P>(v);
}
template <std::size_t N>
void set_words(VlWide<N>& port, const std::vector<uint32_t>& words) {
  for (std::size_t i = 0; i < N; ++i) port[i] = i < words.size() ? words[i] : 0u;
}
template <class P>
void clear_words(P& port) {
  set_words(port, {});
}

// A tree controller model (rc_tracer): the core's ports plus the lights and two lighting ports.
template <class M, class = void>
struct IsTracer : std::false_type {};
template <class M>
struct IsTracer<M, std::void_t<decltype(std::declval<M&>().light_count_i)>> : std::true_type {};

}  // namespace detail

// Every thread's state for the hang report; core_sim.cpp specialises it for the real core models
// (rc_core's debug port dbg_thread_state_o). Other models (the harness test's stand-in) have none.
template <class Model>
std::string thread_states(const Model&) {
  return "";
}

// Every thread's state from rc_core's dbg_thread_state_o (rc_pkg::thread_state_e per thread;
// the names are docs/spec.toml [thread_state]'s, docs/debugging.md).
template <class Word>
std::string describe_thread_states(const Word& st, uint32_t threads) {
  constexpr auto kBits = static_cast<unsigned>(spec::kThreadStateBits);
  std::ostringstream s;
  s << "  threads:";
  for (uint32_t t = 0; t < threads; ++t) {
    const uint64_t v = get_field(st, static_cast<int>(kBits * t), static_cast<int>(kBits));
    s << " " << t << ":"
      << (v < static_cast<uint64_t>(spec::kThreadStateCount) ? spec::kThreadStateNames[v] : "?");
  }
  s << "\n";
  return s.str();
}

template <class Model>
struct CoreSim<Model>::State {
  const scene::SceneImage& image;
  CoreSimOptions opt;
  std::unique_ptr<VerilatedTb<Model>> tb;  // the model, its clock and reset, the waveform
  Model* m = nullptr;                      // tb's model
  std::vector<std::unique_ptr<MemoryPort>> ports;
  std::vector<std::unique_ptr<MemoryPort>> lports;  // a tree controller's lshd, lmat
  std::mt19937_64 rng;
  uint64_t cycle = 0;
  uint64_t quiet = 0;  // cycles since the last handshake on any port
  bool used = false;

  // Packet stream.
  uint32_t width = 0, height = 0;
  uint64_t packets_total = 0, packets_fed = 0;
  std::vector<uint64_t> owner;  // per pixel (slot): the packet whose ray writes it, or kNoOwner
  bool pkt_loaded = false;
  uint32_t gap = 0;
  // Framebuffer.
  uint64_t pixels_total = 0, written = 0, miss_payload = 0;
  std::vector<uint8_t> seen;
  uint32_t fb_low_run = 0;

  State(const scene::SceneImage& img, const CoreSimOptions& o) : image(img), opt(o) {}

  bool stalls() const { return opt.stall_seed != 0; }

  std::string port_state() const {
    std::ostringstream s;
    for (int i = 0; i < kCorePorts; ++i) {
      const MemoryPort& p = *ports[static_cast<size_t>(i)];
      const MemoryStats& st = p.stats();
      s << "  " << core_port_name(i) << " port: " << p.outstanding() << " outstanding, idle "
        << p.idle_cycles() << " cycles, " << st.requests << " requests, " << st.responses
        << " responses";
      if (p.response())
        s << ", showing tag " << p.response()->tag << " (index " << p.response()->index << ")";
      s << "\n";
    }
    for (const auto& p : lports)
      s << "  " << p->name() << " port: " << p->outstanding() << " outstanding, "
        << p->stats().requests << " requests, " << p->stats().responses << " responses\n";
    return s.str();
  }

  std::string describe(const std::string& what) const {
    std::ostringstream s;
    s << what << " (cycle " << cycle << ", " << quiet << " cycles since the last handshake)\n"
      << "  packets fed " << packets_fed << " of " << packets_total << " (pkt_valid_i "
      << int(m->pkt_valid_i) << ", pkt_ready_o " << int(m->pkt_ready_o) << "), pixels written "
      << written << " of " << pixels_total << " (fb_valid_o " << int(m->fb_valid_o)
      << ", fb_ready_i " << int(m->fb_ready_i) << ")\n"
      << "  idle_o " << int(m->idle_o) << ", error_o 0x" << std::hex << int(m->error_o) << std::dec
      << "\n"
      << thread_states(*m) << port_state();
    return s.str();
  }
};

template <class Model>
CoreSim<Model>::CoreSim(const scene::SceneImage& image, const CoreSimOptions& options)
    : s_(std::make_unique<State>(image, options)) {
  State& s = *s_;
  if (!image.format().template is<fp24>())
    throw scene::Error(image.name() + ": the RTL core is built for fp24 (7/16), the image holds " +
                       image.format().name());
  if (s.opt.stall_seed != 0) apply_stall_recipe(s.opt.memory, s.opt.stall_seed);
  s.rng.seed(mix_seed(s.opt.stall_seed ^ 0x5eedf00dull));

  s.ports = make_core_ports(image, s.opt.memory);
  if constexpr (detail::IsTracer<Model>::value)
    s.lports = make_light_ports(image, s.opt.memory[kPortShading], s.opt.memory[kPortMaterials]);

  // Not fatal on error: an assertion ends the run with a CoreSimError, not abort().
  s.tb = std::make_unique<VerilatedTb<Model>>("core", false, std::vector<std::string>{},
                                              !s.opt.trace_path.empty());
  s.m = &s.tb->m();
}

template <class Model>
CoreSim<Model>::~CoreSim() = default;  // the wrapper closes the waveform, then final()'s the model

template <class Model>
CoreSimResult CoreSim<Model>::render(const RenderOptions& render) {
  using T = fp24;
  const PacketSource<T> gen(render.camera, render.width, render.height, render.ray_source);
  const uint32_t pw = (render.width + 1) / 2, ph = (render.height + 1) / 2;
  Feed feed;
  feed.width = render.width;
  feed.height = render.height;
  feed.packets = static_cast<uint64_t>(pw) * ph;
  feed.background = render.background;
  feed.max_bounces = render.max_bounces;
  feed.packet = [&](uint64_t k, CorePacket& p) {
    const auto px = static_cast<uint32_t>(k % pw), py = static_cast<uint32_t>(k / pw);
    p.mask = gen.packet(px, py, p.rays);
    for (unsigned r = 0; r < kPacketRays; ++r)
      p.slot[r] = (2 * py + (r >> 1)) * render.width + 2 * px + (r & 1u);
  };
  return run(feed);
}

template <class Model>
CoreSimResult CoreSim<Model>::trace(const std::vector<CorePacket>& packets, uint32_t width,
                                    uint32_t height, fp24 t_eps) {
  Feed feed;
  feed.width = width;
  feed.height = height;
  feed.packets = packets.size();
  feed.t_eps = t_eps;
  feed.packet = [&](uint64_t k, CorePacket& p) { p = packets[k]; };
  return run(feed);
}

template <class Model>
CoreSimResult CoreSim<Model>::run(const Feed& feed) {
  using T = fp24;
  constexpr unsigned W = T::kWidth;
  State& s = *s_;
  if (s.used) throw std::logic_error("CoreSim: one run per simulation object");
  s.used = true;
  Model& m = *s.m;
  VerilatedTb<Model>& tb = *s.tb;
  // A field of a port; fp24 words and pixel ids are placed by unsigned offsets.
  const auto set_field = [](auto& port, unsigned lsb, unsigned width, uint64_t value) {
    put_field(port, static_cast<int>(lsb), static_cast<int>(width), value);
  };
  const auto start = std::chrono::steady_clock::now();

  // ---- Configuration and reset ----
  const auto bounds = s.image.bounds_bits();
  for (unsigned i = 0; i < 6; ++i) set_field(m.bounds_i, i * W, W, bounds[i]);
  m.node_count_i = s.image.section(static_cast<uint32_t>(spec::kImageSectionIdNodes)).count;
  m.list_count_i = s.image.section(static_cast<uint32_t>(spec::kImageSectionIdLists)).count;
  m.tri_count_i = s.image.section(static_cast<uint32_t>(spec::kImageSectionIdTriangles)).count;
  m.root_node_i = root_node_record(s.image);
  // The values shade() in tb/golden/trace.hpp uses.
  m.ambient_i = shade_ambient<T>().bits();
  m.diffuse_i = shade_diffuse<T>().bits();
  m.background_i = static_cast<uint32_t>(feed.background[0]) |
                   static_cast<uint32_t>(feed.background[1]) << 8 |
                   static_cast<uint32_t>(feed.background[2]) << 16;
  m.t_eps_i = feed.t_eps.bits();
  constexpr bool kTracer = detail::IsTracer<Model>::value;
  if constexpr (kTracer) {
    // The scene's lights and its shadow rays' t_eps (load_geometry(), as the golden model).
    const Geometry<T> g = load_geometry<T>(s.image);
    if (g.lights.empty() || g.lights.size() > static_cast<size_t>(spec::kLightMaxLights))
      throw std::invalid_argument("CoreSim: the tree controller lights 1 to " +
                                  std::to_string(spec::kLightMaxLights) + " lights, " +
                                  s.image.name() + " has " + std::to_string(g.lights.size()));
    m.light_count_i = static_cast<uint8_t>(g.lights.size());
    m.light_dir_i = 0;
    for (unsigned l = 0; l < g.lights.size(); ++l) {
      if (g.lights[l].directional) m.light_dir_i |= static_cast<uint8_t>(1u << l);
      for (unsigned a = 0; a < 3; ++a) {
        set_field(m.light_pos_i, (3 * l + a) * W, W, g.lights[l].pos[a].bits());
        set_field(m.light_col_i, (3 * l + a) * W, W, g.lights[l].color[a].bits());
      }
    }
    m.t_eps_i = g.t_eps.bits();
    if (feed.max_bounces > static_cast<uint32_t>(spec::kLightBounceLimit))
      throw std::invalid_argument("CoreSim: the tree controller traces to depth " +
                                  std::to_string(spec::kLightBounceLimit) + " at most, not " +
                                  std::to_string(feed.max_bounces));
    m.max_bounces_i = static_cast<uint8_t>(feed.max_bounces);
    const LitParams<T> lp = lit_params<T>(feed.max_bounces, feed.background);
    for (unsigned c = 0; c < 3; ++c) set_field(m.bg_i, c * W, W, lp.background[c].bits());
  }
  m.pkt_kind_i = static_cast<uint8_t>(spec::kRayKindPrimary);
  m.pkt_valid_i = 0;
  m.fb_ready_i = 0;
  m.perf_sel_i = 0;
  const auto fail = [&](const std::string& what) { throw CoreSimError(s.describe(what)); };
  // The wrapper's check (an RTL error: a failed assertion, $error or $stop) as a CoreSimError
  // with the harness's state.
  const auto checked = [&](auto&& step) {
    try {
      step();
    } catch (const TbError&) {
      fail("the RTL stopped (an assertion or $stop; see the message above)");
    }
  };
  checked([&] { tb.reset(4); });

  // ---- The frame: every packet's rays and the pixels (slots) they write ----
  s.width = feed.width;
  s.height = feed.height;
  s.packets_total = feed.packets;
  const uint64_t slots = static_cast<uint64_t>(s.width) * s.height;
  s.seen.assign(slots, 0);
  s.owner.assign(slots, kNoOwner);
  std::vector<CorePacket> packets(feed.packets);
  s.pixels_total = 0;  // the writes due: one per existing ray
  std::array<uint64_t, kRayKinds> rays_fed{};
  for (uint64_t k = 0; k < feed.packets; ++k) {
    CorePacket& p = packets[k];
    feed.packet(k, p);
    rays_fed.at(static_cast<size_t>(p.kind)) +=
        static_cast<uint64_t>(__builtin_popcount(p.mask & 0xfu));
    for (unsigned r = 0; r < kPacketRays; ++r) {
      if (!(p.mask >> r & 1u)) continue;
      if (p.slot[r] >= slots || s.owner[p.slot[r]] != kNoOwner)
        throw std::invalid_argument(
            "CoreSim: packet " + std::to_string(k) + " ray " + std::to_string(r) +
            " writes pixel " + std::to_string(p.slot[r]) + ", outside the frame or another ray's");
      s.owner[p.slot[r]] = k;
      ++s.pixels_total;
    }
  }
  CoreSimResult res;
  Frame& f = res.frame;
  f.width = s.width;
  f.height = s.height;
  f.rgb.assign(slots * 3, 0);
  f.hit_tri.assign(slots, -1);
  f.hit_t.assign(slots, 0.0f);
  f.hits.assign(slots, HitRecord{});
  res.pixel_cycle.assign(slots, 0);
  if constexpr (kTracer) {
    f.light_mask.assign(slots, 0);
    f.bounce_tri.assign(slots, -2);
    f.refract_tri.assign(slots, -2);
  }

  const auto load_packet = [&](uint64_t k) {
    const CorePacket& p = packets[k];
    m.pkt_mask_i = static_cast<uint8_t>(p.mask);
    m.pkt_kind_i = static_cast<uint8_t>(p.kind);
    const bool secondary = p.kind != RayKind::kPrimary;
    for (unsigned r = 0; r < kPacketRays; ++r) {
      const bool on = (p.mask >> r & 1u) != 0;
      for (unsigned a = 0; a < 3; ++a) {
        set_field(m.pkt_org_i, (3 * r + a) * W, W, on ? p.rays[r].org[a].bits() : 0u);
        set_field(m.pkt_dir_i, (3 * r + a) * W, W, on ? p.rays[r].dir[a].bits() : 0u);
      }
      set_field(m.pkt_inv_len_i, r * W, W, on ? p.rays[r].inv_len.bits() : 0u);
      set_field(m.pkt_pixel_i, r * 32, 32, on ? p.slot[r] : 0u);
      set_field(m.pkt_t_hi_i, r * W, W, on && secondary ? p.t_hi[r].bits() : 0u);
      set_field(m.pkt_start_tri_i, r * 32, 32,
                on && secondary ? static_cast<uint32_t>(p.start_tri[r]) : 0u);
    }
  };

  auto last_progress = start;
  const auto drive_port = [&](auto& req_ready, auto& rsp_valid, auto& rsp_tag, auto& rsp_data,
                              auto& rsp_error, const MemoryPort& p) {
    req_ready = p.request_ready();
    const auto& r = p.response();
    rsp_valid = r.has_value();
    if (r) {
      rsp_tag = static_cast<std::remove_reference_t<decltype(rsp_tag)>>(r->tag);
      detail::set_words(rsp_data, r->data);
      rsp_error = r->error;
    } else {
      rsp_tag = 0;
      detail::clear_words(rsp_data);
      rsp_error = 0;
    }
  };
  bool handshake = false;
  const auto sample_port = [&](uint64_t req_valid, uint64_t req_tag, uint64_t req_index,
                               uint64_t rsp_ready, MemoryPort& p) {
    try {
      if (req_valid && p.offer_request(static_cast<uint32_t>(req_tag), req_index)) handshake = true;
      if (p.response() && rsp_ready) {
        p.take_response();
        handshake = true;
      }
    } catch (const ProtocolError& e) {
      fail(std::string("memory protocol violation: ") + e.what());
    }
  };

  const bool in_window_possible = !s.opt.trace_path.empty();
  const auto dump = [&](uint64_t time) {
    if (!in_window_possible || s.cycle < s.opt.trace_first || s.cycle > s.opt.trace_last) return;
    if (!tb.tracing()) {
      try {
        tb.open_trace(s.opt.trace_path);
      } catch (const TbError&) {
        throw CoreSimError("--trace " + s.opt.trace_path + ": cannot open the waveform file");
      }
    }
    tb.dump(time);
  };

  bool tail_started = false;
  uint64_t tail = 0;
  while (true) {
    // ---- Inputs for this cycle ----
    if (!s.pkt_loaded && s.packets_fed < s.packets_total && s.gap == 0) {
      load_packet(s.packets_fed);
      s.pkt_loaded = true;
    }
    m.pkt_valid_i = s.pkt_loaded && s.gap == 0;
    if (s.gap > 0) --s.gap;
    bool fb_ready = true;
    if (s.stalls()) {
      fb_ready = !(s.fb_low_run < 8 && (s.rng() & 3u) == 0);
      s.fb_low_run = fb_ready ? 0 : s.fb_low_run + 1;
    }
    m.fb_ready_i = fb_ready;
    drive_port(m.node_req_ready_i, m.node_rsp_valid_i, m.node_rsp_tag_i, m.node_rsp_data_i,
               m.node_rsp_error_i, *s.ports[kPortNodes]);
    drive_port(m.list_req_ready_i, m.list_rsp_valid_i, m.list_rsp_tag_i, m.list_rsp_data_i,
               m.list_rsp_error_i, *s.ports[kPortLists]);
    drive_port(m.tri_req_ready_i, m.tri_rsp_valid_i, m.tri_rsp_tag_i, m.tri_rsp_data_i,
               m.tri_rsp_error_i, *s.ports[kPortTriangles]);
    drive_port(m.shd_req_ready_i, m.shd_rsp_valid_i, m.shd_rsp_tag_i, m.shd_rsp_data_i,
               m.shd_rsp_error_i, *s.ports[kPortShading]);
    drive_port(m.mat_req_ready_i, m.mat_rsp_valid_i, m.mat_rsp_tag_i, m.mat_rsp_data_i,
               m.mat_rsp_error_i, *s.ports[kPortMaterials]);
    if constexpr (kTracer) {
      drive_port(m.lshd_req_ready_i, m.lshd_rsp_valid_i, m.lshd_rsp_tag_i, m.lshd_rsp_data_i,
                 m.lshd_rsp_error_i, *s.lports[0]);
      drive_port(m.lmat_req_ready_i, m.lmat_rsp_valid_i, m.lmat_rsp_tag_i, m.lmat_rsp_data_i,
                 m.lmat_rsp_error_i, *s.lports[1]);
    }
    tb.eval();

    // ---- Handshakes completing at the coming edge ----
    handshake = false;
    sample_port(m.node_req_valid_o, m.node_req_tag_o, m.node_req_index_o, m.node_rsp_ready_o,
                *s.ports[kPortNodes]);
    sample_port(m.list_req_valid_o, m.list_req_tag_o, m.list_req_index_o, m.list_rsp_ready_o,
                *s.ports[kPortLists]);
    sample_port(m.tri_req_valid_o, m.tri_req_tag_o, m.tri_req_index_o, m.tri_rsp_ready_o,
                *s.ports[kPortTriangles]);
    sample_port(m.shd_req_valid_o, m.shd_req_tag_o, m.shd_req_index_o, m.shd_rsp_ready_o,
                *s.ports[kPortShading]);
    sample_port(m.mat_req_valid_o, m.mat_req_tag_o, m.mat_req_index_o, m.mat_rsp_ready_o,
                *s.ports[kPortMaterials]);
    if constexpr (kTracer) {
      sample_port(m.lshd_req_valid_o, m.lshd_req_tag_o, m.lshd_req_index_o, m.lshd_rsp_ready_o,
                  *s.lports[0]);
      sample_port(m.lmat_req_valid_o, m.lmat_req_tag_o, m.lmat_req_index_o, m.lmat_rsp_ready_o,
                  *s.lports[1]);
    }
    if (m.pkt_valid_i && m.pkt_ready_o) {
      res.packet_cycle.push_back(s.cycle);
      ++s.packets_fed;
      s.pkt_loaded = false;
      handshake = true;
      if (s.stalls() && (s.rng() & 3u) == 0) s.gap = 1 + static_cast<uint32_t>(s.rng() % 8);
    }
    if (m.fb_valid_o && m.fb_ready_i) {
      handshake = true;
      const uint64_t pix = m.fb_pixel_o;
      if (pix >= s.owner.size() || s.owner[pix] == kNoOwner)
        fail("framebuffer write to pixel " + std::to_string(pix) +
             ", which no ray of the frame writes (" + std::to_string(s.owner.size()) + " pixels)");
      const uint32_t x = static_cast<uint32_t>(pix % s.width),
                     y = static_cast<uint32_t>(pix / s.width);
      if (s.owner[pix] >= s.packets_fed)
        fail("framebuffer write to pixel (" + std::to_string(x) + ", " + std::to_string(y) +
             ") before its packet was taken");
      if (s.seen[pix])
        fail("pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") written twice");
      s.seen[pix] = 1;
      res.pixel_cycle[pix] = s.cycle;
      ++s.written;
      const uint32_t rgb = m.fb_rgb_o;
      for (int c = 0; c < 3; ++c) f.rgb[3 * pix + c] = static_cast<uint8_t>(rgb >> (8 * c));
      HitRecord h;
      const uint32_t tri = m.fb_tri_o;
      h.t = static_cast<uint32_t>(get_field(m.fb_t_o, 0, W));
      h.u = static_cast<uint32_t>(get_field(m.fb_u_o, 0, W));
      h.v = static_cast<uint32_t>(get_field(m.fb_v_o, 0, W));
      if (m.fb_hit_o) {
        h.tri = static_cast<int32_t>(tri);
        f.hit_tri[pix] = h.tri;
        f.hit_t[pix] = T::from_bits(h.t).to_float();
      } else if (tri != 0 || h.t != 0 || h.u != 0 || h.v != 0) {
        ++s.miss_payload;  // a miss must report zeros; t, u, v stay as reported (they differ)
      }
      f.hits[pix] = h;
      if constexpr (kTracer) {
        f.light_mask[pix] = m.fb_lights_o;
        f.bounce_tri[pix] = static_cast<int32_t>(m.fb_bounce_tri_o);
        f.refract_tri[pix] = static_cast<int32_t>(m.fb_refract_tri_o);
      }
    }
    checked([&] { tb.check(); });

    // ---- The clock edge ----
    dump(2 * s.cycle);
    checked([&] {
      tb.tick([&] {
        dump(2 * s.cycle + 1);
        for (auto& p : s.ports) p->tick();
        for (auto& p : s.lports) p->tick();
      });
    });
    ++s.cycle;
    s.quiet = handshake ? 0 : s.quiet + 1;

    if (m.error_o >> spec::kCoreStatusWatchdog & 1u) fail("the core's watchdog bit is set");
    if (s.quiet > s.opt.watchdog_cycles)
      fail("no handshake on any port for " + std::to_string(s.opt.watchdog_cycles) +
           " cycles: the core hangs");

    if (s.opt.progress) {
      const auto now = std::chrono::steady_clock::now();
      if (now - last_progress > std::chrono::seconds(1)) {
        last_progress = now;
        std::fprintf(stderr, "\r%s: %llu of %llu, %llu cycles", s.opt.progress_label.c_str(),
                     static_cast<unsigned long long>(s.written),
                     static_cast<unsigned long long>(s.pixels_total),
                     static_cast<unsigned long long>(s.cycle));
      }
    }

    // ---- Done: every packet fed, every pixel written, the core idle, no request outstanding,
    // then a few more cycles to catch spurious writes and requests ----
    if (!tail_started) {
      bool outstanding = false;
      for (auto& p : s.ports) outstanding = outstanding || p->outstanding() > 0;
      for (auto& p : s.lports) outstanding = outstanding || p->outstanding() > 0;
      if (s.packets_fed == s.packets_total && s.written == s.pixels_total && m.idle_o &&
          !outstanding)
        tail_started = true;
    } else if (++tail >= 32) {
      break;
    }
  }
  if (s.opt.progress && std::chrono::steady_clock::now() - start > std::chrono::seconds(1))
    std::fprintf(stderr, "\n");
  for (auto& p : s.ports)
    if (p->stats().requests != p->stats().responses || p->outstanding() > 0)
      fail(std::string("requests after the last pixel (") + p->name() + ")");
  for (auto& p : s.lports)
    if (p->stats().requests != p->stats().responses || p->outstanding() > 0)
      fail(std::string("requests after the last pixel (") + p->name() + ")");
  if (s.miss_payload)
    std::fprintf(stderr, "rtl: %llu misses reported with a non-zero hit payload\n",
                 static_cast<unsigned long long>(s.miss_payload));

  // ---- Status and counters ----
  // A counter is exact core.perf_settle_cycles edges after its last event, and perf_o shows the
  // number perf_sel_i named core.perf_read_latency edges before (rc_core's contract). The core is
  // idle, so only the cycle counter moves on meanwhile.
  for (int64_t i = 0; i < spec::kCorePerfSettleCycles; ++i) tb.tick();
  for (int k = 0; k < kCorePerfCount; ++k) {
    m.perf_sel_i = static_cast<uint8_t>(k);
    for (int64_t i = 0; i < spec::kCorePerfReadLatency; ++i) tb.tick();
    res.perf[static_cast<size_t>(k)] = m.perf_o;
  }
  m.perf_sel_i = 0;
  m.eval();
  res.error_bits = m.error_o;
  res.idle = m.idle_o;
  res.cycles = s.cycle;
  res.packets_fed = s.packets_fed;
  res.rays_fed = rays_fed;
  res.fb_writes = s.written;
  res.writes_due = s.pixels_total;
  res.misses_with_payload = s.miss_payload;
  for (int i = 0; i < kCorePorts; ++i)
    res.memory[static_cast<size_t>(i)] = s.ports[static_cast<size_t>(i)]->stats();
  f.counters = counters_from_perf(res.perf, res.error_bits);
  if constexpr (kTracer) {
    res.lit = true;
    res.on_chip_kinds = kTracerKinds;
  }
  tb.flush_trace();
  if (!s.opt.trace_path.empty() && !tb.tracing())
    throw CoreSimError("--trace " + s.opt.trace_path + ": no waveform written: the trace window " +
                       std::to_string(s.opt.trace_first) + ":" + std::to_string(s.opt.trace_last) +
                       " lies after the frame's last cycle " + std::to_string(s.cycle));
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  f.seconds = res.seconds;
  res.cycles_per_second = res.seconds > 0 ? static_cast<double>(res.cycles) / res.seconds : 0.0;
  return res;
}

}  // namespace rc::harness
