#include "image.hpp"

#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace rc::scene {
namespace {

constexpr uint32_t kAlign = spec::kImageSectionAlign;

uint64_t align_up(uint64_t v) { return (v + kAlign - 1) / kAlign * kAlign; }

std::string hex32(uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%08x", v);
  return buf;
}

struct Required {
  uint32_t id;
  int64_t stride;  // 0: the triangle stride, -1: the shading stride (both depend on the format)
};

constexpr Required kRequired[] = {
    {spec::kImageSectionIdNodes, spec::kKdNodeBytes},
    {spec::kImageSectionIdLists, spec::kKdListEntryBytes},
    {spec::kImageSectionIdTriangles, 0},
    {spec::kImageSectionIdShading, -1},
    {spec::kImageSectionIdMaterials, spec::kImageMaterialStride},
    {spec::kImageSectionIdStrings, 1},
    {spec::kImageSectionIdView, spec::kImageViewStride},
    {spec::kImageSectionIdLights, spec::kImageLightStride},
};

}  // namespace

const char* section_name(uint32_t id) {
  switch (id) {
    case spec::kImageSectionIdNodes: return "nodes";
    case spec::kImageSectionIdLists: return "lists";
    case spec::kImageSectionIdTriangles: return "triangles";
    case spec::kImageSectionIdShading: return "shading";
    case spec::kImageSectionIdMaterials: return "materials";
    case spec::kImageSectionIdStrings: return "strings";
    case spec::kImageSectionIdView: return "view";
    case spec::kImageSectionIdLights: return "lights";
    default: return "unknown";
  }
}

void put_le(std::vector<uint8_t>* buf, size_t offset, uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) (*buf)[offset + i] = static_cast<uint8_t>(value >> (8 * i));
}

uint64_t get_le(const uint8_t* p, int bytes) {
  uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= static_cast<uint64_t>(p[i]) << (8 * i);
  return v;
}

void put_f32(std::vector<uint8_t>* buf, size_t offset, float value) {
  uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  put_le(buf, offset, bits, 4);
}

float get_f32(const uint8_t* p) {
  const auto bits = static_cast<uint32_t>(get_le(p, 4));
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

uint32_t material_eta(const NumberFormat& format, uint32_t ior_bits) {
  return format.encode(1.0 / format.decode(ior_bits));
}

uint32_t image_checksum(const std::vector<uint8_t>& image) {
  const size_t at = spec::kImageHeaderChecksum;
  const uint8_t zero[4] = {0, 0, 0, 0};
  uLong crc = crc32(0L, Z_NULL, 0);
  crc = crc32(crc, image.data(), static_cast<uInt>(at));
  crc = crc32(crc, zero, 4);
  // zlib takes uInt lengths: feed the rest in pieces.
  size_t pos = at + 4;
  while (pos < image.size()) {
    const size_t n = std::min<size_t>(image.size() - pos, size_t{1} << 30);
    crc = crc32(crc, image.data() + pos, static_cast<uInt>(n));
    pos += n;
  }
  return static_cast<uint32_t>(crc);
}

// ---- Writer
// ----------------------------------------------------------------------------------------

void ImageWriter::add_section(uint32_t id, std::vector<uint8_t> bytes, uint32_t count,
                              uint32_t stride) {
  if (static_cast<uint64_t>(count) * stride != bytes.size())
    throw Error(std::string("internal error: section ") + section_name(id) + " has " +
                std::to_string(bytes.size()) + " bytes, not count x stride");
  sections_.push_back({id, count, stride, std::move(bytes)});
}

std::vector<uint8_t> ImageWriter::finish() const {
  const uint64_t table = spec::kImageHeaderBytes;
  uint64_t pos = align_up(table + sections_.size() * spec::kImageSectionEntryBytes);
  std::vector<uint64_t> offsets;
  for (const auto& s : sections_) {
    offsets.push_back(pos);
    pos = align_up(pos + s.bytes.size());
  }
  if (pos > UINT32_MAX)
    throw Error("the image would be " + std::to_string(pos) +
                " bytes: more than the format's 32-bit offsets can address");
  std::vector<uint8_t> img(pos, 0);
  put_le(&img, spec::kImageHeaderMagic, spec::kImageMagic, 4);
  put_le(&img, spec::kImageHeaderVersionMajor, spec::kImageVersionMajor, 2);
  put_le(&img, spec::kImageHeaderVersionMinor, spec::kImageVersionMinor, 2);
  put_le(&img, spec::kImageHeaderHeaderBytes, spec::kImageHeaderBytes, 4);
  put_le(&img, spec::kImageHeaderImageBytes, pos, 4);
  put_le(&img, spec::kImageHeaderExpW, static_cast<uint64_t>(format_.exp_w()), 1);
  put_le(&img, spec::kImageHeaderFracW, static_cast<uint64_t>(format_.frac_w()), 1);
  put_le(&img, spec::kImageHeaderValueBytes, static_cast<uint64_t>(format_.value_bytes()), 1);
  put_le(&img, spec::kImageHeaderSectionCount, sections_.size(), 4);
  put_le(&img, spec::kImageHeaderSectionTable, table, 4);
  for (int i = 0; i < 6; ++i) {
    put_f32(&img, spec::kImageHeaderBoundsF32 + 4 * i, bounds_f32[i]);
    put_le(&img, spec::kImageHeaderBoundsValue + 4 * i, bounds_value[i], 4);
  }
  put_le(&img, spec::kImageHeaderRootNode, 0, 4);
  put_le(&img, spec::kImageHeaderTreeDepth, tree_depth, 4);
  put_le(&img, spec::kImageHeaderTriangleCount, triangle_count, 4);
  put_le(&img, spec::kImageHeaderDroppedCount, dropped_count, 4);
  for (size_t i = 0; i < sections_.size(); ++i) {
    const auto& s = sections_[i];
    const size_t e = table + i * spec::kImageSectionEntryBytes;
    put_le(&img, e + spec::kImageSectionId, s.id, 4);
    put_le(&img, e + spec::kImageSectionOffset, offsets[i], 4);
    put_le(&img, e + spec::kImageSectionBytes, s.bytes.size(), 4);
    put_le(&img, e + spec::kImageSectionCount, s.count, 4);
    put_le(&img, e + spec::kImageSectionStride, s.stride, 4);
    std::copy(s.bytes.begin(), s.bytes.end(),
              img.begin() + static_cast<std::ptrdiff_t>(offsets[i]));
  }
  put_le(&img, spec::kImageHeaderChecksum, image_checksum(img), 4);
  return img;
}

// ---- Reader
// ----------------------------------------------------------------------------------------

SceneImage SceneImage::load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open image: " + std::strerror(errno));
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error(path + ": cannot open image: not a regular file");
  if (std::filesystem::file_size(path, ec) > UINT32_MAX)
    throw Error(path + ": too large for an image (offsets are 32-bit)");
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
  if (in.bad()) throw Error(path + ": read error");
  return from_bytes(std::move(bytes), path);
}

SceneImage SceneImage::from_bytes(std::vector<uint8_t> bytes, std::string name) {
  SceneImage img;
  img.name_ = std::move(name);
  img.bytes_ = std::move(bytes);
  img.check();
  return img;
}

void SceneImage::check() {
  const auto fail = [&](const std::string& what) { throw Error(name_ + ": " + what); };
  const uint64_t size = bytes_.size();
  // The magic first: a file that is not an image at all (an OBJ, a PNG) is "not a raycore image"
  // whatever its size; only a file too short to hold the magic is just "truncated".
  if (size >= 4 && u32(spec::kImageHeaderMagic) != spec::kImageMagic)
    fail("not a raycore image: magic " + hex32(u32(spec::kImageHeaderMagic)) + ", expected " +
         hex32(static_cast<uint32_t>(spec::kImageMagic)) + " (\"RCIM\")");
  if (size < static_cast<uint64_t>(spec::kImageHeaderBytes))
    fail("truncated image: " + std::to_string(size) + " bytes, smaller than the " +
         std::to_string(spec::kImageHeaderBytes) + "-byte header");
  if (version_major() != spec::kImageVersionMajor)
    fail("unsupported image version " + std::to_string(version_major()) + "." +
         std::to_string(version_minor()) + ": this reader reads version " +
         std::to_string(spec::kImageVersionMajor) + ".x (rebuild the image)");
  const uint32_t header_bytes = u32(spec::kImageHeaderHeaderBytes);
  if (header_bytes < spec::kImageHeaderBytes || header_bytes > size)
    fail("bad header size " + std::to_string(header_bytes));
  const uint32_t image_bytes = u32(spec::kImageHeaderImageBytes);
  if (size < image_bytes)
    fail("truncated image: the header says " + std::to_string(image_bytes) +
         " bytes, the file has " + std::to_string(size));
  if (size > image_bytes)
    fail(std::to_string(size - image_bytes) +
         " bytes of trailing data after the image (the header says " + std::to_string(image_bytes) +
         " bytes)");
  const uint32_t stored = checksum(), computed = image_checksum(bytes_);
  if (stored != computed)
    fail("checksum mismatch: stored " + hex32(stored) + ", computed " + hex32(computed) +
         " (the image is corrupt)");
  try {
    format_ = NumberFormat::from_widths(static_cast<int>(u32(spec::kImageHeaderExpW, 1)),
                                        static_cast<int>(u32(spec::kImageHeaderFracW, 1)));
  } catch (const Error& e) {
    fail(e.what());
  }
  if (u32(spec::kImageHeaderValueBytes, 1) != static_cast<uint32_t>(format_.value_bytes()))
    fail("value_bytes " + std::to_string(u32(spec::kImageHeaderValueBytes, 1)) +
         " does not match " + format_.name());

  const uint32_t count = u32(spec::kImageHeaderSectionCount);
  const uint32_t table = u32(spec::kImageHeaderSectionTable);
  if (count > spec::kImageMaxSections)
    fail("section count " + std::to_string(count) + " exceeds " +
         std::to_string(spec::kImageMaxSections));
  const uint64_t table_end =
      static_cast<uint64_t>(table) + uint64_t{count} * spec::kImageSectionEntryBytes;
  if (table < header_bytes || table % 4 != 0 || table_end > size)
    fail("section table at " + std::to_string(table) + " (" + std::to_string(count) +
         " entries) is outside the image");
  by_id_.fill(0);
  for (uint32_t i = 0; i < count; ++i) {
    const uint64_t e = table + uint64_t{i} * spec::kImageSectionEntryBytes;
    SectionInfo s;
    s.id = u32(static_cast<int64_t>(e) + spec::kImageSectionId);
    s.offset = u32(static_cast<int64_t>(e) + spec::kImageSectionOffset);
    s.bytes = u32(static_cast<int64_t>(e) + spec::kImageSectionBytes);
    s.count = u32(static_cast<int64_t>(e) + spec::kImageSectionCount);
    s.stride = u32(static_cast<int64_t>(e) + spec::kImageSectionStride);
    const std::string what = std::string("section ") + std::to_string(i) + " (id " +
                             std::to_string(s.id) + ", " + section_name(s.id) + ")";
    if (s.offset % kAlign != 0)
      fail(what + ": offset " + std::to_string(s.offset) + " is not a multiple of " +
           std::to_string(kAlign));
    if (s.offset < table_end || uint64_t{s.offset} + s.bytes > size)
      fail(what + ": bytes [" + std::to_string(s.offset) + ", " +
           std::to_string(uint64_t{s.offset} + s.bytes) + ") are outside the data area [" +
           std::to_string(table_end) + ", " + std::to_string(size) + ")");
    if (uint64_t{s.count} * s.stride != s.bytes)
      fail(what + ": " + std::to_string(s.bytes) + " bytes is not count " +
           std::to_string(s.count) + " x stride " + std::to_string(s.stride));
    for (const auto& other : sections_) {
      if (other.id == s.id) fail(what + ": duplicate section id");
      const bool overlap = s.bytes > 0 && other.bytes > 0 &&
                           s.offset < other.offset + other.bytes &&
                           other.offset < s.offset + s.bytes;
      if (overlap)
        fail(what + " overlaps section id " + std::to_string(other.id) + " (" +
             section_name(other.id) + ")");
    }
    sections_.push_back(s);
    if (s.id < by_id_.size()) by_id_[s.id] = static_cast<int>(sections_.size());
  }
  for (const auto& r : kRequired) {
    if (r.id >= by_id_.size() || by_id_[r.id] == 0)
      fail(std::string("the required section '") + section_name(r.id) + "' (id " +
           std::to_string(r.id) + ") is missing");
    const SectionInfo& s = sections_[by_id_[r.id] - 1];
    const int64_t stride = r.stride > 0 ? r.stride
                           : r.stride == 0
                               ? int64_t{spec::kImageTriangleValues} * format_.value_bytes()
                               : int64_t{shading_stride(format_.value_bytes())};
    if (s.stride != stride)
      fail(std::string("section '") + section_name(r.id) + "' has stride " +
           std::to_string(s.stride) + ", expected " + std::to_string(stride));
  }
  if (section(spec::kImageSectionIdNodes).count == 0) fail("the node section is empty");
  if (section(spec::kImageSectionIdView).count != 1) fail("the view section must hold one record");
  const uint32_t tris = triangle_count();
  if (section(spec::kImageSectionIdTriangles).count != tris ||
      section(spec::kImageSectionIdShading).count != tris)
    fail("triangle and shading sections must hold triangle_count (" + std::to_string(tris) +
         ") records");
  if (root_node() >= node_count())
    fail("root node " + std::to_string(root_node()) + " out of range (" +
         std::to_string(node_count()) + " nodes)");
  // Before version 1.2 a material's eta bytes were reserved (zero): the reader fills them in, so
  // every user (the memory ports the hardware reads) sees a version 1.2 record.
  constexpr uint32_t kMinorWithEta = 2;  // docs/memory-format.md, "Versioning"
  if (version_minor() < kMinorWithEta) {
    const SectionInfo& mats = section(spec::kImageSectionIdMaterials);
    for (uint32_t i = 0; i < mats.count; ++i) {
      const size_t r = mats.offset + size_t{i} * mats.stride;
      const auto ior =
          static_cast<uint32_t>(get_le(bytes_.data() + r + spec::kImageMaterialIor, 4));
      put_le(&bytes_, r + spec::kImageMaterialEta, material_eta(format_, ior), 4);
    }
  }
}

const SectionInfo& SceneImage::section(uint32_t id) const {
  if (id >= by_id_.size() || by_id_[id] == 0)
    throw Error(name_ + ": no section with id " + std::to_string(id));
  return sections_[by_id_[id] - 1];
}

const uint8_t* SceneImage::record(uint32_t id, size_t i) const {
  const SectionInfo& s = section(id);
  if (i >= s.count)
    throw Error(name_ + ": " + section_name(id) + " record " + std::to_string(i) +
                " out of range (" + std::to_string(s.count) + " records)");
  return bytes_.data() + s.offset + i * s.stride;
}

std::array<float, 6> SceneImage::bounds_f32() const {
  std::array<float, 6> b{};
  for (int i = 0; i < 6; ++i) b[i] = get_f32(bytes_.data() + spec::kImageHeaderBoundsF32 + 4 * i);
  return b;
}

std::array<uint32_t, 6> SceneImage::bounds_bits() const {
  std::array<uint32_t, 6> b{};
  for (int i = 0; i < 6; ++i) b[i] = u32(spec::kImageHeaderBoundsValue + 4 * i);
  return b;
}

std::array<double, 6> SceneImage::bounds() const {
  std::array<double, 6> b{};
  const auto bits = bounds_bits();
  for (int i = 0; i < 6; ++i) b[i] = format_.decode(bits[i]);
  return b;
}

KdNode SceneImage::node(size_t i) const {
  return {get_le(record(spec::kImageSectionIdNodes, i), spec::kKdNodeBytes)};
}

uint32_t SceneImage::list_entry(size_t i) const {
  return static_cast<uint32_t>(
      get_le(record(spec::kImageSectionIdLists, i), spec::kKdListEntryBytes));
}

uint32_t SceneImage::triangle_bits(size_t tri, int k) const {
  if (k < 0 || k >= spec::kImageTriangleValues)
    throw Error(name_ + ": triangle value index " + std::to_string(k) + " out of range");
  const int vb = format_.value_bytes();
  return static_cast<uint32_t>(get_le(record(spec::kImageSectionIdTriangles, tri) + k * vb, vb));
}

std::array<uint32_t, 12> SceneImage::triangle_bits(size_t tri) const {
  std::array<uint32_t, 12> m{};
  for (int k = 0; k < 12; ++k) m[k] = triangle_bits(tri, k);
  return m;
}

std::array<double, 12> SceneImage::triangle_values(size_t tri) const {
  std::array<double, 12> m{};
  for (int k = 0; k < 12; ++k) m[k] = format_.decode(triangle_bits(tri, k));
  return m;
}

ShadingRecord SceneImage::shading(size_t tri) const {
  const uint8_t* p = record(spec::kImageSectionIdShading, tri);
  const int vb = format_.value_bytes();
  ShadingRecord r;
  r.material = static_cast<uint32_t>(get_le(p + spec::kImageShadingMaterial, 4));
  for (int k = 0; k < 3; ++k)
    r.normal_bits[k] = static_cast<uint32_t>(
        get_le(p + shading_value_offset(static_cast<int>(spec::kImageShadingNormal) + k, vb), vb));
  r.normal_len_bits = static_cast<uint32_t>(
      get_le(p + shading_value_offset(static_cast<int>(spec::kImageShadingNormalLen), vb), vb));
  return r;
}

MaterialRecord SceneImage::material(size_t i) const {
  const uint8_t* p = record(spec::kImageSectionIdMaterials, i);
  const auto word = [&](int64_t off) { return static_cast<uint32_t>(get_le(p + off, 4)); };
  MaterialRecord m;
  m.illum = word(spec::kImageMaterialIllum);
  m.flags = word(spec::kImageMaterialFlags);
  for (int k = 0; k < 3; ++k) {
    m.kd[k] = word(spec::kImageMaterialKd + 4 * k);
    m.ks[k] = word(spec::kImageMaterialKs + 4 * k);
    m.ke[k] = word(spec::kImageMaterialKe + 4 * k);
    m.tf[k] = word(spec::kImageMaterialTf + 4 * k);
  }
  m.ns = word(spec::kImageMaterialNs);
  m.mirror = word(spec::kImageMaterialMirror);
  m.transmit = word(spec::kImageMaterialTransmit);
  m.dissolve = word(spec::kImageMaterialDissolve);
  m.ior = word(spec::kImageMaterialIor);
  m.eta = word(spec::kImageMaterialEta);
  const SectionInfo& strings = section(spec::kImageSectionIdStrings);
  const uint32_t off = word(spec::kImageMaterialName);
  if (off < strings.bytes) {
    const char* s = reinterpret_cast<const char*>(bytes_.data() + strings.offset + off);
    m.name.assign(s, strnlen(s, strings.bytes - off));
  }
  return m;
}

ViewRecord SceneImage::view() const {
  const uint8_t* p = record(spec::kImageSectionIdView, 0);
  ViewRecord v;
  for (int k = 0; k < 3; ++k) {
    v.eye[k] = get_f32(p + spec::kImageViewEye + 4 * k);
    v.look[k] = get_f32(p + spec::kImageViewLook + 4 * k);
    v.up[k] = get_f32(p + spec::kImageViewUp + 4 * k);
    v.background[k] = get_f32(p + spec::kImageViewBackground + 4 * k);
  }
  v.fov_deg = get_f32(p + spec::kImageViewFov);
  v.width = static_cast<uint32_t>(get_le(p + spec::kImageViewWidth, 4));
  v.height = static_cast<uint32_t>(get_le(p + spec::kImageViewHeight, 4));
  v.flags = static_cast<uint32_t>(get_le(p + spec::kImageViewFlags, 4));
  return v;
}

LightRecord SceneImage::light(size_t i) const {
  const uint8_t* p = record(spec::kImageSectionIdLights, i);
  LightRecord l;
  l.type = static_cast<uint32_t>(get_le(p + spec::kImageLightType, 4));
  for (int k = 0; k < 3; ++k) {
    l.position[k] = get_f32(p + spec::kImageLightPosition + 4 * k);
    l.color[k] = get_f32(p + spec::kImageLightColor + 4 * k);
  }
  l.intensity = get_f32(p + spec::kImageLightIntensity);
  return l;
}

std::vector<std::string> SceneImage::validate(size_t max_problems) const {
  Validation v = validation(max_problems);
  if (v.total > v.problems.size())
    v.problems.push_back("... and " + std::to_string(v.total - v.problems.size()) +
                         " more problems");
  return std::move(v.problems);
}

Validation SceneImage::validation(size_t max_listed) const {
  Validation result;
  std::vector<std::string>& out = result.problems;
  size_t& total = result.total;
  const auto problem = [&](const std::string& what) {
    if (out.size() < max_listed) out.push_back(what);
    ++total;
  };
  const NumberFormat& f = format_;

  // Bounds: finite format values, min <= max, and the float32 copy containing them.
  const auto bb = bounds_bits();
  const auto bf = bounds_f32();
  std::array<double, 6> box{};
  for (int i = 0; i < 6; ++i) {
    if (!f.finite_bits(bb[i])) problem("bounds value " + std::to_string(i) + " is not finite");
    box[i] = f.decode(bb[i]);
  }
  for (int a = 0; a < 3; ++a) {
    if (!(box[a] <= box[a + 3])) problem("bounds: min > max on axis " + std::to_string(a));
    if (!(static_cast<double>(bf[a]) <= box[a]) || !(static_cast<double>(bf[a + 3]) >= box[a + 3]))
      problem("float32 bounds do not contain the format bounds on axis " + std::to_string(a));
  }

  // The tree: every node reached exactly once from the root, children after their parent and
  // in range, finite splits strictly inside the node's box, leaf ranges inside the list section,
  // entries naming live triangles, depth within the limit and equal to the header's.
  const size_t n = node_count(), nl = list_size(), nt = triangle_count();
  if (root_node() != 0) problem("root node is " + std::to_string(root_node()) + ", not 0");
  std::vector<uint8_t> seen(n, 0);
  struct Item {
    uint32_t index;
    uint32_t depth;
    std::array<double, 6> box;
  };
  std::vector<Item> stack{{0, 0, box}};
  uint32_t max_depth = 0;
  while (!stack.empty()) {
    const Item it = stack.back();
    stack.pop_back();
    if (seen[it.index]++) {
      problem("node " + std::to_string(it.index) + " is reached more than once");
      continue;
    }
    max_depth = std::max(max_depth, it.depth);
    const KdNode node = this->node(it.index);
    const std::string at = "node " + std::to_string(it.index) + ": ";
    if (node.is_leaf()) {
      if (uint64_t{node.first()} + node.count() > nl) {
        problem(at + "list range [" + std::to_string(node.first()) + ", +" +
                std::to_string(node.count()) + ") exceeds the list section (" + std::to_string(nl) +
                " entries)");
        continue;
      }
      for (uint32_t k = 0; k < node.count(); ++k) {
        const uint32_t t = list_entry(node.first() + k);
        if (t >= nt)
          problem(at + "list entry " + std::to_string(node.first() + k) + " names triangle " +
                  std::to_string(t) + ", out of range (" + std::to_string(nt) + " triangles)");
        else if (triangle_dropped(t))
          problem(at + "list entry names dropped triangle " + std::to_string(t));
      }
      continue;
    }
    const int axis = node.axis();
    const uint32_t left = node.left();
    if (left <= it.index) {
      problem(at + "left child " + std::to_string(left) + " is not after the node");
      continue;
    }
    if (uint64_t{left} + 1 >= n) {
      problem(at + "children " + std::to_string(left) + ", " + std::to_string(left + 1) +
              " out of range (" + std::to_string(n) + " nodes)");
      continue;
    }
    if (!f.finite_bits(node.split_bits())) {
      problem(at + "split value " + std::to_string(node.split_bits()) +
              " is not a finite format value");
      continue;
    }
    const double s = f.decode(node.split_bits());
    if (!(s > it.box[axis] && s < it.box[axis + 3]))
      problem(at + "split " + std::to_string(s) + " is not strictly inside the node's box");
    if (it.depth + 1 > spec::kKdtreeMaxDepth)
      problem(at + "children deeper than the maximum depth " +
              std::to_string(spec::kKdtreeMaxDepth));
    Item l{left, it.depth + 1, it.box}, r{left + 1, it.depth + 1, it.box};
    l.box[axis + 3] = s;
    r.box[axis] = s;
    stack.push_back(r);
    stack.push_back(l);
  }
  size_t unreachable = 0;
  for (size_t i = 0; i < n; ++i) unreachable += seen[i] == 0;
  if (unreachable) problem(std::to_string(unreachable) + " nodes are not reachable from the root");
  if (max_depth != tree_depth())
    problem("header tree depth " + std::to_string(tree_depth()) + ", the tree is " +
            std::to_string(max_depth) + " deep");

  // Triangles and shading records: dropped triangles are all-zero and have no material.
  const size_t nm = material_count();
  size_t dropped = 0;
  for (size_t t = 0; t < nt; ++t) {
    const ShadingRecord sr = shading(t);
    const auto m = triangle_bits(t);
    const bool zero = std::all_of(m.begin(), m.end(), [](uint32_t b) { return b == 0; });
    if (sr.dropped()) {
      ++dropped;
      const bool shade_zero =
          sr.normal_len_bits == 0 && std::all_of(sr.normal_bits.begin(), sr.normal_bits.end(),
                                                 [](uint32_t b) { return b == 0; });
      if (!zero || !shade_zero)
        problem("triangle " + std::to_string(t) + " is dropped but its record is not zero");
      if (sr.material != ShadingRecord::kDropped)
        problem("triangle " + std::to_string(t) + ": material word of a dropped triangle is not " +
                std::to_string(ShadingRecord::kDropped));
      continue;
    }
    if (zero) problem("triangle " + std::to_string(t) + " has an all-zero record but a material");
    if (sr.material >= nm)
      problem("triangle " + std::to_string(t) + ": material " + std::to_string(sr.material) +
              " out of range (" + std::to_string(nm) + " materials)");
    for (uint32_t b : m)
      if (!f.finite_bits(b)) {
        problem("triangle " + std::to_string(t) + " has a non-finite transform value");
        break;
      }
  }
  if (dropped != dropped_count())
    problem("header says " + std::to_string(dropped_count()) + " dropped triangles, found " +
            std::to_string(dropped));

  const SectionInfo& strings = section(spec::kImageSectionIdStrings);
  for (size_t i = 0; i < nm; ++i) {
    const uint8_t* p = record(spec::kImageSectionIdMaterials, i);
    const auto off = static_cast<uint32_t>(get_le(p + spec::kImageMaterialName, 4));
    const uint8_t* s = bytes_.data() + strings.offset;
    if (off >= strings.bytes || std::find(s + off, s + strings.bytes, 0) == s + strings.bytes)
      problem("material " + std::to_string(i) + ": name offset " + std::to_string(off) +
              " is not a NUL-terminated string in the string section");
    const MaterialRecord m = material(i);
    if (m.eta != material_eta(f, m.ior))
      problem("material " + std::to_string(i) + ": eta " + hex32(m.eta) + " is not 1 / ior (" +
              hex32(material_eta(f, m.ior)) + ")");
  }
  const ViewRecord v = view();
  if (v.width == 0 || v.height == 0) problem("view: zero resolution");
  for (size_t i = 0; i < light_count(); ++i) {
    const uint32_t type = light(i).type;
    if (type != spec::kImageLightTypePoint && type != spec::kImageLightTypeDirectional)
      problem("light " + std::to_string(i) + ": unknown type " + std::to_string(type));
  }
  return result;
}

}  // namespace rc::scene
