// fuzz_image: libFuzzer target for the memory-image reader and validator
// (rc::scene::SceneImage::from_bytes and validate(), tb/scene/image.cpp) and, for images the
// validator passes, the golden model (rc::load_geometry, tb/golden/geometry.cpp, and a 4x4
// render_golden, tb/golden/render.cpp).
//
// Input: a memory image (docs/memory-format.md; seeds in corpus/fuzz_image/, made from tiny scenes
// by gen_seed_images.cpp). The image carries a CRC-32 and its own length, which random mutations
// almost never keep right, so when the bytes as given are rejected the target patches the header's
// image_bytes (to the input's length) and checksum fields and reads the image again: the reader's
// size and checksum checks still run on the unpatched bytes, everything after them gets to see
// mutated images.
//
// Per loaded image the target calls what `raycore scene info` prints (tb/app/scene_command.cpp
// run_info: header fields, bounds, counts, every section, material names, the view, the lights)
// and every record accessor, then validate(). When validate() lists no problem it also decodes the
// geometry (fp24 or fp32 by the image's format) and renders 4x4 pixels with threads=1: with a fixed
// camera, and with the image's own view camera (host rays and ray-generator rays) when that camera
// is valid. A validated image must render without error bits (the validator checks everything the
// hardware flags, and depth <= max_depth keeps the stack within stack_depth).
//
// RC_FUZZ_RENDER_UNVALIDATED=1 in the environment also renders the images that fail validation
// (without the error-bit check): the golden model must survive what the hardware is said to flag.
// In that mode corpus/fuzz_image/broken-shared-children-dag.rcimg (inner nodes sharing their
// children, which only the validator rejects) times out: a packet visits 2^20 nodes.
//
// Correct outcomes: rc::scene::Error from from_bytes() or load_geometry (but not "internal
// error: ..."), std::runtime_error from the golden model (camera or size checks). Findings:
// sanitizer reports, other exceptions, hangs, huge allocations, an Error from an accessor or from
// validate() on a loaded image (validate() lists problems, the accessors are called within the
// counts), and error bits from rendering a validated image.
//
// Build and run: `make fuzz` (tests/fuzz/fuzz.mk). By hand: build/fuzz/fuzz_image CORPUS_DIR, or
// build/fuzz/fuzz_image FILE to replay one input.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iomanip>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "camera.hpp"
#include "error.hpp"
#include "fuzz_common.hpp"
#include "geometry.hpp"
#include "image.hpp"
#include "render.hpp"

namespace {

using rc::fuzz::fuzz_fail;

// What run_info prints, into a string; plus every record through its accessor.
void inspect(const rc::scene::SceneImage& img, std::ostringstream& o) {
  const auto& f = img.format();
  o << img.name() << " " << img.bytes().size() << " " << img.version_major() << "."
    << img.version_minor() << " " << img.checksum() << " " << f.name() << " " << f.value_bytes()
    << " " << f.width() << "\n";
  o << std::setprecision(9);
  for (double b : img.bounds()) o << b << " ";
  for (uint32_t b : img.bounds_bits()) o << std::hex << b << std::dec << " ";
  for (float b : img.bounds_f32()) o << b << " ";
  o << img.triangle_count() << " " << img.dropped_count() << " " << img.root_node() << " "
    << img.node_count() << " " << img.list_size() << " " << img.tree_depth() << "\n";
  for (size_t i = 0; i < img.material_count(); ++i) {
    const auto m = img.material(i);
    o << m.name << " " << m.illum << " " << m.flags << " " << m.kd[0] << " " << m.mirror << "\n";
  }
  o << std::setprecision(6);
  const auto v = img.view();
  o << v.width << "x" << v.height << " " << v.eye[0] << " " << v.look[1] << " " << v.up[2] << " "
    << v.fov_deg << " " << v.background[0] << " " << v.flags << "\n";
  for (size_t i = 0; i < img.light_count(); ++i) {
    const auto l = img.light(i);
    o << l.type << " " << l.position[0] << " " << l.color[1] << " " << l.intensity << "\n";
  }
  for (const auto& s : img.sections())
    o << s.id << " " << rc::scene::section_name(s.id) << " " << s.offset << " " << s.bytes << " "
      << s.count << " " << s.stride << "\n";
  uint64_t sum = 0;
  for (size_t i = 0; i < img.node_count(); ++i) {
    const rc::scene::KdNode n = img.node(i);
    sum += n.kind() + n.index() + n.value() + n.is_leaf();
  }
  for (size_t i = 0; i < img.list_size(); ++i) sum += img.list_entry(i);
  for (size_t t = 0; t < img.triangle_count(); ++t) {
    for (uint32_t b : img.triangle_bits(t)) sum += b;
    for (double d : img.triangle_values(t)) sum += d == d;
    const auto s = img.shading(t);
    sum += s.material + s.normal_len_bits + s.dropped();
  }
  o << sum << "\n";
}

template <class T>
void render_checked(const rc::Geometry<T>& g, const rc::Camera& cam, rc::RaySource src,
                    const char* what, bool validated) {
  rc::RenderOptions opt;
  opt.width = 4;
  opt.height = 4;
  opt.camera = cam;
  opt.threads = 1;
  opt.progress = false;
  opt.ray_source = src;
  const rc::Frame f = rc::render_golden(g, opt);
  if (validated && (f.counters.errors != 0 || f.counters.error_bits != 0))
    fuzz_fail(std::string("a validated image renders with error bits ") +
              std::to_string(f.counters.error_bits) + " (" + what + ")");
}

template <class T>
void golden(const rc::scene::SceneImage& img, bool validated) {
  const rc::Geometry<T> g = rc::load_geometry<T>(img);
  rc::Camera fixed;
  fixed.eye = {1.5, 1.25, 5.0};
  fixed.look = {0.0, 0.0, 0.0};
  fixed.up = {0.0, 1.0, 0.0};
  fixed.fov_deg = 45.0;
  render_checked(g, fixed, rc::RaySource::kHost, "fixed camera", validated);

  const auto v = img.view();
  rc::Camera view;
  view.eye = {v.eye[0], v.eye[1], v.eye[2]};
  view.look = {v.look[0], v.look[1], v.look[2]};
  view.up = {v.up[0], v.up[1], v.up[2]};
  view.fov_deg = v.fov_deg;
  try {
    rc::validate_camera(view);
  } catch (const std::runtime_error&) {
    return;  // the image's camera is not usable: nothing more to render
  }
  render_checked(g, view, rc::RaySource::kHost, "view camera, host rays", validated);
  render_checked(g, view, rc::RaySource::kRayGen, "view camera, ray generator", validated);
}

void run(const rc::scene::SceneImage& img) {
  std::ostringstream o;
  inspect(img, o);
  const bool validated = img.validate().empty();
  // RC_FUZZ_RENDER_UNVALIDATED=1 renders images that fail validation too (load_geometry
  // permitting): the golden model's own checks (the error bits) against what the hardware is said
  // to flag.
  static const bool unvalidated = [] {
    const char* e = std::getenv("RC_FUZZ_RENDER_UNVALIDATED");
    return e && std::string(e) == "1";
  }();
  if (!validated && !unvalidated) return;
  try {
    if (img.format().is<rc::fp24>())
      golden<rc::fp24>(img, validated);
    else if (img.format().is<rc::fp32ftz>())
      golden<rc::fp32ftz>(img, validated);
  } catch (const rc::scene::Error&) {
    // load_geometry rejects (e.g. a format it has no instantiation for): correct.
  } catch (const std::runtime_error&) {
    // The golden model's own checks: correct. (rc::scene::Error is caught above.)
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::optional<rc::scene::SceneImage> img;
  try {
    try {
      img.emplace(
          rc::scene::SceneImage::from_bytes(std::vector<uint8_t>(data, data + size), "fuzz.rcimg"));
    } catch (const rc::scene::Error&) {
      if (size < static_cast<size_t>(rc::spec::kImageHeaderBytes) || size > UINT32_MAX) return 0;
      // Patch image_bytes and the checksum, and read again (unless nothing changed).
      std::vector<uint8_t> bytes(data, data + size);
      rc::scene::put_le(&bytes, rc::spec::kImageHeaderImageBytes, size, 4);
      rc::scene::put_le(&bytes, rc::spec::kImageHeaderChecksum, rc::scene::image_checksum(bytes),
                        4);
      if (std::equal(bytes.begin(), bytes.end(), data)) return 0;
      img.emplace(rc::scene::SceneImage::from_bytes(std::move(bytes), "fuzz.rcimg"));
    }
  } catch (const rc::scene::Error& e) {
    // Rejected input: a correct outcome (unless the message admits an internal error).
    rc::fuzz::check_error_message(e.what());
    return 0;
  } catch (...) {
    fuzz_fail(rc::fuzz::describe_current_exception());
  }
  // A loaded image: the accessors and validate() must not throw (validate() lists problems).
  try {
    run(*img);
  } catch (const rc::scene::Error& e) {
    fuzz_fail(std::string("an accessor or validate() threw on a loaded image: ") + e.what());
  } catch (...) {
    fuzz_fail(rc::fuzz::describe_current_exception());
  }
  return 0;
}
