// The memory image: write/read round trip through the reader's typed accessors, the checksum rule,
// and every load-time and validate() error.
#include <gtest/gtest.h>
#include <zlib.h>

#include <fstream>
#include <functional>
#include <glm/geometric.hpp>

#include "compiler.hpp"
#include "error.hpp"
#include "fp.hpp"
#include "test_util.hpp"

namespace rc::test {
namespace {

using rc::scene::Compiled;
using rc::scene::CompileOptions;
using rc::scene::Error;
using rc::scene::KdNode;
using rc::scene::NumberFormat;
using rc::scene::SceneImage;
namespace spec = rc::spec;

const Compiled& cornell() {
  static const Compiled c =
      rc::scene::compile_scene(rc::scene::builtin_scene("cornell"), CompileOptions());
  return c;
}

std::string load_error(const std::vector<uint8_t>& bytes) {
  try {
    SceneImage::from_bytes(bytes, "test.rcimg");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Image, WriteReadRoundTrip) {
  const rc::scene::Scene scene = rc::scene::builtin_scene("spheres");
  const Compiled c = rc::scene::compile_scene(scene, CompileOptions());
  const std::string path = temp_dir() + "/spheres.rcimg";
  {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(c.image.data()),
              static_cast<std::streamsize>(c.image.size()));
  }
  const SceneImage img = SceneImage::load(path);
  EXPECT_EQ(img.bytes(), c.image);
  EXPECT_EQ(img.version_major(), static_cast<uint32_t>(spec::kImageVersionMajor));
  EXPECT_EQ(img.version_minor(), static_cast<uint32_t>(spec::kImageVersionMinor));
  EXPECT_TRUE(img.format() == NumberFormat::fp24());
  EXPECT_EQ(img.value_bytes(), 3);
  EXPECT_EQ(img.triangle_count(), c.stats.triangles);
  EXPECT_EQ(img.node_count(), c.stats.nodes);
  EXPECT_EQ(img.list_size(), c.stats.references);
  EXPECT_EQ(img.tree_depth(), c.stats.depth);
  EXPECT_EQ(img.root_node(), 0u);
  EXPECT_EQ(img.bytes().size() % spec::kImageSectionAlign, 0u);
  EXPECT_EQ(img.section(spec::kImageSectionIdTriangles).stride, 36u);
  EXPECT_EQ(img.section(spec::kImageSectionIdShading).stride, 16u);
  for (const auto& s : img.sections()) EXPECT_EQ(s.offset % spec::kImageSectionAlign, 0u);
  // Bounds: format values, the float32 copy equal to them.
  const auto b = img.bounds();
  const auto bf = img.bounds_f32();
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(static_cast<double>(bf[i]), b[i]);
    EXPECT_EQ(b[i], c.stats.bounds[i]);
  }
  // Typed accessors.
  size_t cases = 0, bad = 0;
  for (size_t t = 0; t < img.triangle_count(); ++t) {
    const auto m = img.triangle<rc::fp24>(t);
    const auto bits = img.triangle_bits(t);
    const auto vals = img.triangle_values(t);
    for (int k = 0; k < 12; ++k) {
      ++cases;
      bad += m[k].bits() != bits[k] || m[k].to_double() != vals[k];
    }
    const auto sh = img.shading(t);
    ++cases;
    bad += sh.material != scene.meshes[0].material[t];
    const auto& tri = scene.meshes[0].triangles[t];
    const auto& v = scene.meshes[0].vertices;
    const glm::dvec3 n = glm::cross(v[tri[1]] - v[tri[0]], v[tri[2]] - v[tri[0]]);
    const double len = std::sqrt(glm::dot(n, n));
    for (int k = 0; k < 3; ++k) {
      ++cases;
      bad += sh.normal_bits[k] != img.format().encode(n[k] / len);
    }
    ++cases;
    bad += sh.normal_len_bits != img.format().encode(len);
  }
  report_cases("image round trip: triangle and shading records", cases, bad);
  EXPECT_EQ(bad, 0u);
  ASSERT_EQ(img.material_count(), scene.meshes[0].materials.size());
  for (size_t i = 0; i < img.material_count(); ++i) {
    const auto m = img.material(i);
    const auto& want = scene.meshes[0].materials[i];
    EXPECT_EQ(m.name, want.name);
    EXPECT_EQ(m.illum, static_cast<uint32_t>(want.illum));
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(m.kd[k], img.format().encode(want.kd[k]));
      EXPECT_EQ(m.ks[k], img.format().encode(want.ks[k]));
      EXPECT_EQ(m.ke[k], img.format().encode(want.ke[k]));
      EXPECT_EQ(m.tf[k], img.format().encode(want.tf[k]));
    }
    EXPECT_EQ(m.ns, img.format().encode(want.ns));
    EXPECT_EQ(m.ior, img.format().encode(want.ior));
    EXPECT_EQ(m.dissolve, img.format().encode(want.dissolve));
    EXPECT_EQ(m.mirror, img.format().encode(want.mirror()));
    EXPECT_EQ(m.transmit, img.format().encode(want.transmit()));
    // eta: the format value nearest 1 / ior (ior as stored), checked against both neighbours.
    const NumberFormat& f = img.format();
    const double inv = 1.0 / f.decode(m.ior), eta = f.decode(m.eta);
    EXPECT_LE(std::abs(eta - inv), std::abs(f.next_up(eta) - inv)) << want.name;
    EXPECT_LE(std::abs(eta - inv), std::abs(f.next_down(eta) - inv)) << want.name;
  }
  const auto view = img.view();
  EXPECT_EQ(view.width, scene.width);
  EXPECT_EQ(view.height, scene.height);
  EXPECT_EQ(view.eye[1], static_cast<float>(scene.camera->eye.y));
  EXPECT_EQ(view.fov_deg, static_cast<float>(scene.camera->fov_deg));
  EXPECT_EQ(view.flags, 0u);
  ASSERT_EQ(img.light_count(), 1u);
  EXPECT_EQ(img.light(0).position[0], static_cast<float>(scene.lights[0].position.x));
  EXPECT_EQ(img.light(0).type, static_cast<uint32_t>(spec::kImageLightTypePoint));
  EXPECT_TRUE(img.validate().empty());
  // Node words decode to the same fields they were encoded from.
  for (size_t i = 0; i < img.node_count(); ++i) {
    const KdNode n = img.node(i);
    const KdNode again = n.is_leaf() ? KdNode::leaf(n.first(), n.count())
                                     : KdNode::inner(n.axis(), n.left(), n.split_bits());
    ASSERT_EQ(again.raw, n.raw);
  }
  EXPECT_THROW(img.node(img.node_count()), Error);
  EXPECT_THROW(img.triangle_bits(img.triangle_count(), 0), Error);
  EXPECT_THROW(img.material(img.material_count()), Error);
}

TEST(Image, Fp32Images) {
  CompileOptions opt;
  opt.format = NumberFormat::fp32();
  const Compiled c = rc::scene::compile_scene(rc::scene::builtin_scene("cornell"), opt);
  const SceneImage img = SceneImage::from_bytes(c.image);
  EXPECT_TRUE(img.format() == NumberFormat::fp32());
  EXPECT_EQ(img.value_bytes(), 4);
  EXPECT_EQ(img.section(spec::kImageSectionIdTriangles).stride, 48u);
  EXPECT_EQ(img.section(spec::kImageSectionIdShading).stride, 32u);
  const auto m = img.triangle<rc::fp32ftz>(0);
  EXPECT_EQ(m[0].bits(), img.triangle_bits(0, 0));
  EXPECT_THROW(img.triangle<rc::fp24>(0), Error);
  EXPECT_TRUE(img.validate().empty());
}

TEST(Image, ChecksumIsCrc32WithTheFieldZeroed) {
  std::vector<uint8_t> bytes = cornell().image;
  const uint32_t stored =
      static_cast<uint32_t>(rc::scene::get_le(bytes.data() + spec::kImageHeaderChecksum, 4));
  for (int i = 0; i < 4; ++i) bytes[spec::kImageHeaderChecksum + i] = 0;
  const uint32_t crc = static_cast<uint32_t>(
      crc32(crc32(0L, Z_NULL, 0), bytes.data(), static_cast<uInt>(bytes.size())));
  EXPECT_EQ(stored, crc);
}

struct Corruption {
  std::string name;
  std::function<void(std::vector<uint8_t>*, const SceneImage&)> apply;
  std::string expect;  // a substring of the error
};

TEST(Image, LoadErrors) {
  const SceneImage good = SceneImage::from_bytes(cornell().image);
  const size_t entry0 = spec::kImageHeaderBytes;  // the first section table entry
  const size_t e = spec::kImageSectionEntryBytes;
  const std::vector<Corruption> cases = {
      {"empty file", [](auto* b, auto&) { b->clear(); }, "truncated"},
      {"shorter than the header", [](auto* b, auto&) { b->resize(100); }, "truncated"},
      {"truncated", [](auto* b, auto&) { b->resize(b->size() - 64); }, "truncated"},
      {"truncated by one byte", [](auto* b, auto&) { b->pop_back(); }, "truncated"},
      {"trailing data", [](auto* b, auto&) { b->push_back(0); }, "trailing"},
      {"wrong magic", [](auto* b, auto&) { (*b)[0] = 'X'; }, "not a raycore image"},
      {"wrong major version",
       [](auto* b, auto&) { patch(b, spec::kImageHeaderVersionMajor, 2, 2), fix_checksum(b); },
       "unsupported image version 2." + std::to_string(spec::kImageVersionMinor)},
      {"checksum mismatch", [](auto* b, auto&) { (*b)[b->size() / 2] ^= 0x40; },
       "checksum mismatch"},
      {"checksum field changed", [](auto* b, auto&) { (*b)[spec::kImageHeaderChecksum] ^= 1; },
       "checksum mismatch"},
      {"unsupported format",
       [](auto* b, auto&) { patch(b, spec::kImageHeaderFracW, 10, 1), fix_checksum(b); },
       "unsupported number format"},
      {"value bytes wrong",
       [](auto* b, auto&) { patch(b, spec::kImageHeaderValueBytes, 4, 1), fix_checksum(b); },
       "value_bytes"},
      {"too many sections",
       [](auto* b, auto&) { patch(b, spec::kImageHeaderSectionCount, 1000, 4), fix_checksum(b); },
       "section count"},
      {"table outside the image",
       [](auto* b, auto&) {
         patch(b, spec::kImageHeaderSectionTable, 1u << 30, 4), fix_checksum(b);
       },
       "section table"},
      {"section misaligned",
       [&](auto* b, auto&) {
         patch(b, entry0 + spec::kImageSectionOffset, 400, 4), fix_checksum(b);
       },
       "not a multiple of 64"},
      {"section beyond the end",
       [&](auto* b, auto&) {
         patch(b, entry0 + spec::kImageSectionOffset, b->size() - 64, 4), fix_checksum(b);
       },
       "outside the data area"},
      {"section over the header",
       [&](auto* b, auto&) { patch(b, entry0 + spec::kImageSectionOffset, 0, 4), fix_checksum(b); },
       "outside the data area"},
      {"sections overlap",
       [&](auto* b, auto& img) {
         patch(b, entry0 + e + spec::kImageSectionOffset, img.sections()[0].offset, 4);
         fix_checksum(b);
       },
       "overlaps"},
      {"bytes not count x stride",
       [&](auto* b, auto&) { patch(b, entry0 + spec::kImageSectionCount, 3, 4), fix_checksum(b); },
       "is not count"},
      {"duplicate section id",
       [&](auto* b, auto&) {
         patch(b, entry0 + e + spec::kImageSectionId, spec::kImageSectionIdNodes, 4),
             fix_checksum(b);
       },
       "duplicate section id"},
      {"required section missing",
       [&](auto* b, auto&) {
         patch(b, entry0 + e + spec::kImageSectionId, 99, 4), fix_checksum(b);
       },
       "required section 'lists'"},
      {"wrong triangle stride",
       [&](auto* b, auto& img) {
         // Triangle section: claim stride 12 (and a count that keeps bytes = count x stride).
         const size_t at = entry0 + 2 * e;
         patch(b, at + spec::kImageSectionStride, 12, 4);
         patch(b, at + spec::kImageSectionCount, img.sections()[2].bytes / 12, 4);
         fix_checksum(b);
       },
       "stride 12, expected 36"},
      {"triangle count differs",
       [&](auto* b, auto&) { patch(b, spec::kImageHeaderTriangleCount, 31, 4), fix_checksum(b); },
       "triangle_count"},
      {"root out of range",
       [&](auto* b, auto&) { patch(b, spec::kImageHeaderRootNode, 1u << 20, 4), fix_checksum(b); },
       "root node"},
  };
  size_t mismatches = 0;
  for (const auto& c : cases) {
    std::vector<uint8_t> bytes = cornell().image;
    c.apply(&bytes, good);
    const std::string err = load_error(bytes);
    const bool ok = err.find(c.expect) != std::string::npos && err.find("test.rcimg") == 0;
    mismatches += !ok;
    EXPECT_TRUE(ok) << c.name << ": expected an error containing '" << c.expect << "', got '" << err
                    << "'";
  }
  report_cases("image load errors", cases.size(), mismatches);
  // A missing file.
  try {
    SceneImage::load(temp_dir() + "/no-such.rcimg");
    ADD_FAILURE() << "no error for a missing file";
  } catch (const Error& err) {
    EXPECT_NE(std::string(err.what()).find("no-such.rcimg: cannot open image"), std::string::npos);
  }
}

// Materials: an image of version 1.1 (no eta, its bytes zero) reads with every eta filled in as
// the compiler writes it; an eta that is not 1 / ior is a validate() problem.
TEST(Image, MaterialEta) {
  const SceneImage good = SceneImage::from_bytes(cornell().image);
  const auto& mats = good.section(spec::kImageSectionIdMaterials);
  ASSERT_GT(mats.count, 0u);
  std::vector<uint8_t> old = cornell().image;
  patch(&old, spec::kImageHeaderVersionMinor, 1, 2);
  for (uint32_t i = 0; i < mats.count; ++i)
    patch(&old, mats.offset + i * mats.stride + spec::kImageMaterialEta, 0, 4);
  fix_checksum(&old);
  const SceneImage read = SceneImage::from_bytes(old);
  EXPECT_EQ(read.version_minor(), 1u);
  for (uint32_t i = 0; i < mats.count; ++i) {
    EXPECT_NE(good.material(i).eta, 0u);
    EXPECT_EQ(read.material(i).eta, good.material(i).eta) << "material " << i;
  }
  EXPECT_TRUE(read.validate().empty());

  std::vector<uint8_t> bad = cornell().image;
  patch(&bad, mats.offset + spec::kImageMaterialEta, good.material(0).eta + 1, 4);
  fix_checksum(&bad);
  const auto problems = SceneImage::from_bytes(bad).validate();
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("material 0: eta"), std::string::npos) << problems[0];
  EXPECT_NE(problems[0].find("is not 1 / ior"), std::string::npos) << problems[0];
}

// validate(): hand-made malformed trees and records in an otherwise valid image.
TEST(Image, ValidateFindsMalformedTrees) {
  const SceneImage good = SceneImage::from_bytes(cornell().image);
  ASSERT_TRUE(good.validate().empty());
  const auto& nodes = good.section(spec::kImageSectionIdNodes);
  const auto& lists = good.section(spec::kImageSectionIdLists);
  const auto& shading = good.section(spec::kImageSectionIdShading);
  // Find an inner node and a non-empty leaf.
  size_t inner = 0, leaf = 0;
  for (size_t i = 0; i < good.node_count(); ++i) {
    if (!good.node(i).is_leaf()) inner = i;
    if (good.node(i).is_leaf() && good.node(i).count() > 0) leaf = i;
  }
  const KdNode in = good.node(inner), lf = good.node(leaf);
  const auto node_at = [&](size_t i) { return nodes.offset + i * spec::kKdNodeBytes; };
  const uint32_t nan_bits = rc::fp24::nan().bits(), inf_bits = rc::fp24::inf().bits();
  const uint32_t n = static_cast<uint32_t>(good.node_count());
  struct Bad {
    std::string name;
    std::function<void(std::vector<uint8_t>*)> apply;
    std::string expect;
  };
  const std::vector<Bad> cases = {
      {"child out of range",
       [&](auto* b) {
         patch(b, node_at(inner), KdNode::inner(in.axis(), n - 1, in.split_bits()).raw, 8);
       },
       "out of range"},
      {"child not after its parent",
       [&](auto* b) {
         patch(b, node_at(inner),
               KdNode::inner(in.axis(), static_cast<uint32_t>(inner), in.split_bits()).raw, 8);
       },
       "is not after the node"},
      {"NaN split",
       [&](auto* b) {
         patch(b, node_at(inner), KdNode::inner(in.axis(), in.left(), nan_bits).raw, 8);
       },
       "not a finite format value"},
      {"infinite split",
       [&](auto* b) {
         patch(b, node_at(inner), KdNode::inner(in.axis(), in.left(), inf_bits).raw, 8);
       },
       "not a finite format value"},
      {"split bits above the format width",
       [&](auto* b) {
         patch(b, node_at(inner),
               KdNode::inner(in.axis(), in.left(), in.split_bits() | (1u << 30)).raw, 8);
       },
       "not a finite format value"},
      {"split outside the node's box",
       [&](auto* b) {
         patch(b, node_at(0),
               KdNode::inner(good.node(0).axis(), good.node(0).left(),
                             rc::fp24::from_double(1e6).bits())
                   .raw,
               8);
       },
       "not strictly inside"},
      {"leaf range beyond the lists",
       [&](auto* b) {
         patch(b, node_at(leaf),
               KdNode::leaf(lf.first(), static_cast<uint32_t>(good.list_size() + 1)).raw, 8);
       },
       "exceeds the list section"},
      {"list entry out of range",
       [&](auto* b) { patch(b, lists.offset + lf.first() * 4u, 1000, 4); },
       "out of range (32 triangles)"},
      {"unreachable nodes", [&](auto* b) { patch(b, node_at(0), KdNode::leaf(0, 0).raw, 8); },
       "not reachable"},
      {"depth differs from the header",
       [&](auto* b) { patch(b, spec::kImageHeaderTreeDepth, 31, 4); }, "header tree depth"},
      {"dropped flag with a non-zero record",
       [&](auto* b) { patch(b, shading.offset, rc::scene::ShadingRecord::kDropped, 4); },
       "is dropped but its record is not zero"},
      {"material out of range", [&](auto* b) { patch(b, shading.offset, 77, 4); },
       "material 77 out of range"},
  };
  size_t mismatches = 0;
  for (const auto& c : cases) {
    std::vector<uint8_t> bytes = cornell().image;
    c.apply(&bytes);
    fix_checksum(&bytes);
    const auto problems = SceneImage::from_bytes(bytes).validate();
    bool found = false;
    for (const auto& p : problems) found = found || p.find(c.expect) != std::string::npos;
    mismatches += !found;
    std::string all;
    for (const auto& p : problems) all += "\n  " + p;
    EXPECT_TRUE(found) << c.name << ": expected a problem containing '" << c.expect
                       << "', got:" << all;
  }
  report_cases("validate() malformed images", cases.size(), mismatches);
}

}  // namespace
}  // namespace rc::test
