// The raycore memory image (docs/memory-format.md): writer helpers and the reader.
//
// One little-endian, versioned image holds everything the golden model, the verilated RTL and the
// FPGA build read: kd-tree nodes, leaf triangle lists, unit-triangle transforms, shading records,
// materials, the view and the lights. Every constant (magic, version, offsets, strides, node bit
// fields, section ids) comes from docs/spec.toml through the generated rc_constants.hpp.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "error.hpp"
#include "number_format.hpp"
#include "rc_constants.hpp"

namespace rc::scene {

// ---- kd-tree nodes: one 64-bit word each -------------------------------------------------------

struct KdNode {
  uint64_t raw = 0;

  static constexpr uint64_t kKindMask = (uint64_t{1} << spec::kKdNodeKindBits) - 1;
  static constexpr uint64_t kIndexMask = (uint64_t{1} << spec::kKdNodeIndexBits) - 1;
  static constexpr uint64_t kValueMask = (uint64_t{1} << spec::kKdNodeValueBits) - 1;
  static constexpr uint32_t kMaxIndex = static_cast<uint32_t>(kIndexMask);

  static KdNode inner(int axis, uint32_t left, uint32_t split_bits) {
    return {(static_cast<uint64_t>(axis) << spec::kKdNodeKindLsb) |
            (static_cast<uint64_t>(left) << spec::kKdNodeIndexLsb) |
            (static_cast<uint64_t>(split_bits) << spec::kKdNodeValueLsb)};
  }
  static KdNode leaf(uint32_t first, uint32_t count) {
    return {(static_cast<uint64_t>(spec::kKdNodeKindLeaf) << spec::kKdNodeKindLsb) |
            (static_cast<uint64_t>(first) << spec::kKdNodeIndexLsb) |
            (static_cast<uint64_t>(count) << spec::kKdNodeValueLsb)};
  }

  uint32_t kind() const { return static_cast<uint32_t>((raw >> spec::kKdNodeKindLsb) & kKindMask); }
  bool is_leaf() const { return kind() == spec::kKdNodeKindLeaf; }
  int axis() const { return static_cast<int>(kind()); }  // inner nodes only
  uint32_t index() const {
    return static_cast<uint32_t>((raw >> spec::kKdNodeIndexLsb) & kIndexMask);
  }
  uint32_t value() const {
    return static_cast<uint32_t>((raw >> spec::kKdNodeValueLsb) & kValueMask);
  }
  // Inner nodes: children are an adjacent pair.
  uint32_t left() const { return index(); }
  uint32_t right() const { return index() + 1; }
  uint32_t split_bits() const { return value(); }
  // Leaves: a range of the list section.
  uint32_t first() const { return index(); }
  uint32_t count() const { return value(); }
};

// ---- Records
// -------------------------------------------------------------------------------------

struct SectionInfo {
  uint32_t id = 0;
  uint32_t offset = 0;
  uint32_t bytes = 0;
  uint32_t count = 0;
  uint32_t stride = 0;
};

// The name of a section id ("nodes", ...), or "unknown".
const char* section_name(uint32_t id);

// The shading record stride for a number format with value_bytes bytes per packed value.
constexpr uint32_t shading_stride(int value_bytes) {
  const auto unit = static_cast<uint32_t>(spec::kImageShadingStrideUnit);
  const auto need = static_cast<uint32_t>(spec::kImageShadingFirstValue +
                                          spec::kImageShadingValues * value_bytes);
  return (need + unit - 1) / unit * unit;
}
// Byte offset of packed value k (spec::kImageShadingNormal + axis, spec::kImageShadingNormalLen)
// inside a shading record.
constexpr uint32_t shading_value_offset(int k, int value_bytes) {
  return static_cast<uint32_t>(spec::kImageShadingFirstValue + k * value_bytes);
}

struct ShadingRecord {
  static constexpr uint32_t kDropped = uint32_t{1} << spec::kImageShadingDroppedBit;
  uint32_t material = 0;                  // kDropped (bit dropped_bit alone) for a dropped triangle
  std::array<uint32_t, 3> normal_bits{};  // unit geometric normal n / |n|, format values
  uint32_t normal_len_bits = 0;           // |n| = |(B-A) x (C-A)|, a format value
  bool dropped() const { return (material & kDropped) != 0; }
};

struct MaterialRecord {
  std::string name;
  uint32_t illum = 0;
  uint32_t flags = 0;
  // Format values (bit patterns): kd, ks, ke, tf rgb; ns, ior, dissolve, mirror, transmit, eta.
  std::array<uint32_t, 3> kd{}, ks{}, ke{}, tf{};
  uint32_t ns = 0, ior = 0, dissolve = 0, mirror = 0, transmit = 0, eta = 0;
};

// A material's eta (docs/memory-format.md, "Materials"): 1 / ior, computed in double from ior's
// format value (bits) and rounded to the format once.
uint32_t material_eta(const NumberFormat& format, uint32_t ior_bits);

struct ViewRecord {
  std::array<float, 3> eye{}, look{}, up{};
  float fov_deg = 0.0f;
  uint32_t width = 0, height = 0;
  std::array<float, 3> background{};
  uint32_t flags = 0;
};

struct LightRecord {
  uint32_t type = 0;
  std::array<float, 3> position{};  // the travel direction, for directional lights
  std::array<float, 3> color{};
  float intensity = 0.0f;
};

// ---- Little-endian byte access
// -------------------------------------------------------------------

void put_le(std::vector<uint8_t>* buf, size_t offset, uint64_t value, int bytes);
uint64_t get_le(const uint8_t* p, int bytes);
void put_f32(std::vector<uint8_t>* buf, size_t offset, float value);
float get_f32(const uint8_t* p);

// ---- Writer
// ----------------------------------------------------------------------------------------

// Assembles an image: sections are placed in the order added, each at a 64-byte boundary after
// the header and section table; the image is padded with zeros to a 64-byte multiple; the checksum
// is filled in last.
class ImageWriter {
 public:
  explicit ImageWriter(NumberFormat format) : format_(format) {}

  // Header fields (the rest are derived).
  std::array<float, 6> bounds_f32{};       // min xyz, max xyz
  std::array<uint32_t, 6> bounds_value{};  // the same as format bit patterns
  uint32_t tree_depth = 0;
  uint32_t triangle_count = 0;
  uint32_t dropped_count = 0;

  void add_section(uint32_t id, std::vector<uint8_t> bytes, uint32_t count, uint32_t stride);
  std::vector<uint8_t> finish() const;

 private:
  struct Pending {
    uint32_t id, count, stride;
    std::vector<uint8_t> bytes;
  };
  NumberFormat format_;
  std::vector<Pending> sections_;
};

// CRC-32 (zlib's crc32) over the image with the checksum field taken as zero.
uint32_t image_checksum(const std::vector<uint8_t>& image);

// ---- Reader
// ----------------------------------------------------------------------------------------

// What SceneImage::validation() found: the first problems (one line each) and how many there are
// in all (total > problems.size() when the list was cut short; total == 0: well formed).
struct Validation {
  std::vector<std::string> problems;
  size_t total = 0;
  bool ok() const { return total == 0; }
};

// A loaded, checked image. load() and from_bytes() check everything that can be checked without
// walking the tree (size, magic, version, number format, section table, checksum, the required
// sections and their strides and counts) and throw Error with a message naming the image.
// validate() walks the tree and the records and lists what is malformed.
class SceneImage {
 public:
  static SceneImage load(const std::string& path);
  static SceneImage from_bytes(std::vector<uint8_t> bytes, std::string name = "<memory>");

  const std::string& name() const { return name_; }
  const std::vector<uint8_t>& bytes() const { return bytes_; }

  // Header.
  uint32_t version_major() const { return u32(spec::kImageHeaderVersionMajor, 2); }
  uint32_t version_minor() const { return u32(spec::kImageHeaderVersionMinor, 2); }
  uint32_t checksum() const { return u32(spec::kImageHeaderChecksum); }
  const NumberFormat& format() const { return format_; }
  int value_bytes() const { return format_.value_bytes(); }
  std::array<float, 6> bounds_f32() const;
  std::array<uint32_t, 6> bounds_bits() const;
  std::array<double, 6> bounds() const;  // the format values, exactly
  uint32_t root_node() const { return u32(spec::kImageHeaderRootNode); }
  uint32_t tree_depth() const { return u32(spec::kImageHeaderTreeDepth); }
  uint32_t triangle_count() const { return u32(spec::kImageHeaderTriangleCount); }
  uint32_t dropped_count() const { return u32(spec::kImageHeaderDroppedCount); }

  const std::vector<SectionInfo>& sections() const { return sections_; }
  const SectionInfo& section(uint32_t id) const;  // a required section

  // kd-tree nodes and leaf lists.
  size_t node_count() const { return section(spec::kImageSectionIdNodes).count; }
  KdNode node(size_t i) const;
  size_t list_size() const { return section(spec::kImageSectionIdLists).count; }
  uint32_t list_entry(size_t i) const;

  // Triangle i's unit-triangle transform M (3x4, row-major m00 m01 m02 m03 m10 ... m23).
  uint32_t triangle_bits(size_t tri, int k) const;
  std::array<uint32_t, 12> triangle_bits(size_t tri) const;
  std::array<double, 12> triangle_values(size_t tri) const;
  // As values of the format type T (rc::fp24 or rc::fp32ftz); throws Error if the image has
  // another format.
  template <class T>
  std::array<T, 12> triangle(size_t tri) const {
    check_format<T>();
    std::array<T, 12> m{};
    for (int k = 0; k < 12; ++k) m[k] = T::from_bits(triangle_bits(tri, k));
    return m;
  }
  template <class T>
  T split(const KdNode& n) const {
    check_format<T>();
    return T::from_bits(n.split_bits());
  }
  bool triangle_dropped(size_t tri) const { return shading(tri).dropped(); }

  ShadingRecord shading(size_t tri) const;
  size_t material_count() const { return section(spec::kImageSectionIdMaterials).count; }
  MaterialRecord material(size_t i) const;
  ViewRecord view() const;
  size_t light_count() const { return section(spec::kImageSectionIdLights).count; }
  LightRecord light(size_t i) const;

  // Walks the tree from the root and checks every record; returns one line per problem (an empty
  // list means well formed): the first max_problems, then "... and N more problems" if there are
  // more. See docs/memory-format.md, "Malformed images".
  std::vector<std::string> validate(size_t max_problems = 20) const;
  // The same walk: the first max_listed problems and the total count.
  Validation validation(size_t max_listed = 20) const;

 private:
  SceneImage() : format_(NumberFormat::fp24()) {}
  void check();
  template <class T>
  void check_format() const {
    if (!format_.is<T>())
      throw Error(name_ + ": the image holds " + format_.name() + " values, not " +
                  std::to_string(T::kExpW) + "/" + std::to_string(T::kFracW));
  }
  uint32_t u32(int64_t offset, int bytes = 4) const {
    return static_cast<uint32_t>(get_le(bytes_.data() + offset, bytes));
  }
  const uint8_t* record(uint32_t id, size_t i) const;

  std::string name_;
  std::vector<uint8_t> bytes_;
  NumberFormat format_;
  std::vector<SectionInfo> sections_;
  std::array<int, 16> by_id_{};  // index into sections_ + 1 for ids < 16
};

}  // namespace rc::scene
