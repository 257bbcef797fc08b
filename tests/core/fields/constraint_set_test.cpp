#include "core/fields/constraint_set.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/mesh/hex_to_tets.h"
#include "core/mesh/tet_topology.h"
#include "core/util/error.h"
#include "core/util/text_file.h"
#include "tests/core/io/io_test_util.h"
#include "tests/core/test_meshes.h"

namespace facehex {
namespace {

namespace fs = std::filesystem;

// The unit cube as 2 x 2 x 2 hexes split into tets: 27 vertices on the grid {0, 0.5, 1}^3, vertex (i, j, k) at
// (i, j, k) / 2 with id (3k + j) * 3 + i, the centre (13) the only interior one. Sides: x = 0 u0, x = 1 u1, z = 0 v0,
// z = 1 v1, y = 0 w0, y = 1 w1.
struct Cube {
  VolumeMesh hex = test::hex_box(2, 2, 2);
  Eigen::MatrixXd V = hex.V;
  Eigen::MatrixXi T = split_into_tets(hex).T;
  Eigen::VectorXi mask = side_mask_of(hex);
  std::vector<char> boundary = boundary_vertex_flags(27, boundary_faces(T).F);
};

int id(int i, int j, int k) { return (3 * k + j) * 3 + i; }

// The ids of the cube's vertices whose grid index passes `keep`, ascending.
std::vector<int> grid_ids(const std::function<bool(int, int, int)>& keep) {
  std::vector<int> out;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i)
        if (keep(i, j, k)) out.push_back(id(i, j, k));
  std::sort(out.begin(), out.end());
  return out;
}

void expect_error(const std::function<void()>& run, const std::string& subject, const std::vector<std::string>& words) {
  try {
    run();
    ADD_FAILURE() << "expected facehex::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.subject(), subject) << e.what();
    for (const std::string& w : words)
      EXPECT_NE(std::string(e.what()).find(w), std::string::npos) << "'" << e.what() << "' lacks '" << w << "'";
  }
}

using test::TempDir;

Selection by_plane(const PlaneSelection& p) {
  Selection s;
  s.plane = p;
  return s;
}

PlaneSelection plane_x(double x, double band) {
  PlaneSelection p;
  p.point = Eigen::Vector3d(x, 0, 0);
  p.normal = Eigen::Vector3d::UnitX();
  p.band = band;
  return p;
}

Constraint constraint(const std::string& name, int field, double value, const Selection& select) {
  Constraint c;
  c.name = name;
  c.field = field;
  c.value = value;
  c.select = select;
  return c;
}

// ---------------------------------------------------------------------------------------------------------------
// Reading and writing

// The example of core/fields/constraint_set.h.
const char* const kHeaderExample = R"json({
  "format": "facehex-constraints", "version": 1,
  "constraints": [
    {"name": "outer (skin)", "field": "w", "value": 1, "select": {"side": "w1"}},
    {"name": "mid-sagittal", "field": "u", "value": 0.5,
     "select": {"plane": {"point": [0, 0, 0], "normal": [1, 0, 0]}, "band": 1.0, "region": "volume",
                "within": {"center": [0, 80, -60], "radius": 40}}},
    {"name": "picked", "field": "v", "value": 0.7, "select": {"ids": [12, 13, 14]}}
  ]
})json";

TEST(ConstraintSetFile, ParsesTheHeadersExample) {
  const ConstraintSet set = parse_constraint_set(kHeaderExample, "example.json");
  ASSERT_EQ(set.constraints.size(), 3u);
  const Constraint &skin = set.constraints[0], &mid = set.constraints[1], &picked = set.constraints[2];
  EXPECT_EQ(skin.name, "outer (skin)");
  EXPECT_EQ(skin.field, 2);
  EXPECT_EQ(skin.value, 1.0);
  ASSERT_TRUE(skin.select.side.has_value());
  EXPECT_EQ(*skin.select.side, W1);
  EXPECT_FALSE(skin.select.plane.has_value());
  EXPECT_TRUE(skin.select.ids.empty());

  EXPECT_EQ(mid.field, 0);
  EXPECT_EQ(mid.value, 0.5);
  ASSERT_TRUE(mid.select.plane.has_value());
  const PlaneSelection& p = *mid.select.plane;
  EXPECT_EQ(p.point, Eigen::Vector3d::Zero());
  EXPECT_EQ(p.normal, Eigen::Vector3d::UnitX());
  EXPECT_EQ(p.band, 1.0);
  EXPECT_EQ(p.region, "volume");
  ASSERT_TRUE(p.within_center.has_value());
  EXPECT_EQ(*p.within_center, Eigen::Vector3d(0, 80, -60));
  EXPECT_EQ(p.within_radius, 40.0);
  EXPECT_EQ(p.exclude_sides, 0);

  EXPECT_EQ(picked.field, 1);
  EXPECT_EQ(picked.value, 0.7);
  EXPECT_EQ(picked.select.ids, (std::vector<int>{12, 13, 14}));
}

TEST(ConstraintSetFile, DefaultsAndNormalization) {
  const ConstraintSet set = parse_constraint_set(R"({"format": "facehex-constraints", "version": 1, "constraints": [
      {"field": "u", "value": 0, "select": {"side": "u0"}},
      {"field": "v", "value": 0.25, "select": {"plane": {"point": [1, 2, 3], "normal": [0, 3, 4]},
                                                "exclude": ["u0", "v1"]}}]})",
                                                 "defaults.json");
  ASSERT_EQ(set.constraints.size(), 2u);
  EXPECT_EQ(set.constraints[0].name, "constraint 1");  // unnamed constraints are numbered from 1
  EXPECT_EQ(set.constraints[1].name, "constraint 2");
  const PlaneSelection& p = *set.constraints[1].select.plane;
  EXPECT_LT((p.normal - Eigen::Vector3d(0, 0.6, 0.8)).norm(), 1e-15);  // normalized
  EXPECT_EQ(p.band, 1.0);                                              // default: 1 mm
  EXPECT_EQ(p.region, "volume");                                       // default
  EXPECT_FALSE(p.within_center.has_value());
  EXPECT_EQ(p.exclude_sides, side_bit(U0) | side_bit(V1));
}

TEST(ConstraintSetFile, WritesAndReadsBackEveryKindOfSelection) {
  PlaneSelection full;
  full.point = Eigen::Vector3d(1.5, -2.25, 1.0 / 3.0);
  full.normal = Eigen::Vector3d(0, 1, 0);
  full.band = 0.375;
  full.region = "boundary";
  full.within_center = Eigen::Vector3d(0.1, 0.2, -7.0 / 3.0);
  full.within_radius = 12.5;
  full.exclude_sides = side_bit(U1) | side_bit(W0);
  PlaneSelection on_side = plane_x(-4, 2);
  on_side.region = "w1";
  Selection ids;
  ids.ids = {9, 2, 5};
  Selection side;
  side.side = V1;
  ConstraintSet set;
  set.constraints = {constraint("picked", 1, 1.0 / 3.0, ids), constraint("top", 1, 1, side),
                     constraint("full plane", 0, 0.5, by_plane(full)), constraint("on w1", 2, 0.1, by_plane(on_side))};

  TempDir dir;
  const std::string path = dir.file("set.json");
  write_constraint_set(path, set);
  const ConstraintSet back = read_constraint_set(path);
  ASSERT_EQ(back.constraints.size(), set.constraints.size());
  for (size_t i = 0; i < set.constraints.size(); ++i) {
    const Constraint &a = set.constraints[i], &b = back.constraints[i];
    SCOPED_TRACE(a.name);
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.field, a.field);
    EXPECT_EQ(b.value, a.value);  // bit for bit, 1/3 included
    EXPECT_EQ(b.select.ids, a.select.ids);
    EXPECT_EQ(b.select.side, a.select.side);
    ASSERT_EQ(b.select.plane.has_value(), a.select.plane.has_value());
    if (!a.select.plane) continue;
    const PlaneSelection &p = *a.select.plane, &q = *b.select.plane;
    EXPECT_EQ(q.point, p.point);
    EXPECT_EQ(q.normal, p.normal);
    EXPECT_EQ(q.band, p.band);
    EXPECT_EQ(q.region, p.region);
    EXPECT_EQ(q.within_center, p.within_center);
    EXPECT_EQ(q.within_radius, p.within_radius);
    EXPECT_EQ(q.exclude_sides, p.exclude_sides);
  }
  EXPECT_EQ(to_json(back), to_json(set));
  EXPECT_EQ(read_text_file(path), to_json(set));
}

TEST(ConstraintSetFile, BundledSetsReadAndWriteBackUnchanged) {
  for (const std::string name : {"artisynth-refface", "headsq-template"}) {
    SCOPED_TRACE(name);
    const std::string path = std::string(FACEHEX_RESOURCE_DIR) + "/standards/" + name + "/constraints.json";
    const ConstraintSet set = read_constraint_set(path);
    // The six shape ends first, then the four feature lines of the paper (README of each standard).
    ASSERT_EQ(set.constraints.size(), 10u);
    const ConstraintSet sides = side_constraints();
    for (int s = 0; s < kNumSides; ++s) {
      EXPECT_EQ(set.constraints[s].select.side, sides.constraints[s].select.side);
      EXPECT_EQ(set.constraints[s].field, sides.constraints[s].field);
      EXPECT_EQ(set.constraints[s].value, sides.constraints[s].value);
    }
    EXPECT_EQ(set.constraints[6].name, "mid-sagittal line");
    EXPECT_EQ(set.constraints[6].field, 0);
    EXPECT_EQ(set.constraints[6].value, 0.5);
    EXPECT_EQ(to_json(parse_constraint_set(to_json(set), "again")), to_json(set));
  }
}

TEST(ConstraintSetFile, AMissingFileIsAnErrorNamingIt) {
  const std::string path = "/nonexistent/facehex/constraints.json";
  expect_error([&] { read_constraint_set(path); }, path, {"cannot open"});
}

TEST(ConstraintSetFile, ABadFileOnDiskIsAnErrorNamingIt) {
  TempDir dir;
  const std::string path = dir.file("bad.json");
  write_text_file(path, R"({"format": "facehex-constraints", "version": 1, "constraints": [
      {"name": "lip", "field": "q", "value": 0.5, "select": {"ids": [1]}}]})");
  expect_error([&] { read_constraint_set(path); }, path, {"constraint 'lip'", "field must be"});
}

// Every bad input the parser checks: an Error whose subject is the file and whose message names the constraint (when
// the fault is inside one) and the fault.
TEST(ConstraintSetFile, RejectsBadFilesNamingTheFileAndTheConstraint) {
  const std::string head = R"({"format": "facehex-constraints", "version": 1, "constraints": [)";
  const std::string good = R"({"field": "u", "value": 0, "select": {"side": "u0"}}, )";
  // One constraint named "lip" with the given body (field, value and select).
  const auto lip = [&](const std::string& body) { return head + good + R"({"name": "lip", )" + body + "}]}"; };
  const std::string plane = R"("plane": {"point": [0, 0, 0], "normal": [1, 0, 0]})";
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"{\"format\": ", {"not valid JSON"}},
      {"", {"not valid JSON"}},
      {R"({"format": "other", "version": 1, "constraints": []})", {"\"format\" must be \"facehex-constraints\""}},
      {R"({"version": 1, "constraints": []})", {"\"format\" must be"}},
      {R"({"format": "facehex-constraints", "version": 2, "constraints": []})", {"unsupported \"version\""}},
      {R"({"format": "facehex-constraints", "constraints": []})", {"unsupported \"version\""}},
      {R"({"format": "facehex-constraints", "version": "1", "constraints": []})", {"unsupported \"version\""}},
      {R"({"format": "facehex-constraints", "version": 1.5, "constraints": []})", {"unsupported \"version\""}},
      {R"({"format": "facehex-constraints", "version": 1})", {"constraints"}},
      {lip(R"("value": 0.5, "select": {"ids": [1]})"), {"constraint 'lip'", "field"}},
      {lip(R"("field": "x", "value": 0.5, "select": {"ids": [1]})"), {"constraint 'lip'", "field must be"}},
      {lip(R"("field": 1, "value": 0.5, "select": {"ids": [1]})"), {"constraint 'lip'", "string"}},
      {lip(R"("field": "u", "select": {"ids": [1]})"), {"constraint 'lip'", "value"}},
      {lip(R"("field": "u", "value": "0.5", "select": {"ids": [1]})"), {"constraint 'lip'", "number"}},
      {lip(R"("field": "u", "value": 1e400, "select": {"ids": [1]})"), {"not valid JSON", "1e400"}},
      {lip(R"("field": "u", "value": 0.5)"), {"constraint 'lip'", "select"}},
      {lip(R"("field": "u", "value": 0.5, "select": {})"), {"constraint 'lip'", "exactly one of"}},
      {lip(R"("field": "u", "value": 0.5, "select": {"ids": [1], "side": "u0"})"),
       {"constraint 'lip'", "exactly one of"}},
      {lip(R"("field": "u", "value": 0.5, "select": {"side": "v1", )" + plane + "}"),
       {"constraint 'lip'", "exactly one of"}},
      {lip(R"("field": "u", "value": 0.5, "select": {"side": "u2"})"), {"constraint 'lip'", "unknown side 'u2'"}},
      {lip(R"("field": "u", "value": 0.5, "select": {"side": "U0"})"), {"constraint 'lip'", "unknown side 'U0'"}},
      {lip(R"("field": "u", "value": 0.5, "select": {"ids": [4, -3]})"), {"constraint 'lip'", "negative vertex id -3"}},
      {lip(R"("field": "u", "value": 0.5, "select": {"ids": ["a"]})"), {"constraint 'lip'", "vertex id \"a\""}},
      {lip(R"("field": "u", "value": 0.5, "select": {"ids": [1.7]})"), {"constraint 'lip'", "vertex id 1.7"}},
      {lip(R"("field": "u", "value": 0.5, "select": {"ids": 5})"), {"constraint 'lip'", "\"ids\" must be an array"}},
      {lip(R"("field": "u", "value": 7.5, "select": {"ids": [1]})"), {"constraint 'lip'", "value 7.5 is outside 0..1"}},
      {lip(R"("field": "u", "value": -0.5, "select": {"ids": [1]})"),
       {"constraint 'lip'", "value -0.5 is outside 0..1"}},
      {lip(R"("field": "u", "value": 0.5, "select": {"plane": {"point": [0, 0], "normal": [1, 0, 0]}})"),
       {"constraint 'lip'", "plane.point must be an array of 3 numbers"}},
      {lip(R"("field": "u", "value": 0.5, "select": {"plane": {"point": [0, 0, 0], "normal": 1}})"),
       {"constraint 'lip'", "plane.normal must be an array of 3 numbers"}},
      {lip(R"("field": "u", "value": 0.5, "select": {"plane": {"point": [0, 0, 0], "normal": [0, 0, 0]}})"),
       {"constraint 'lip'", "plane.normal is zero"}},
      {lip(R"("field": "u", "value": 0.5, "select": {"plane": {"point": [0, 0, 0], "normal": ["1", 0, 0]}})"),
       {"constraint 'lip'", "number"}},
      {lip(R"("field": "u", "value": 0.5, "select": {"plane": {"normal": [1, 0, 0]}})"), {"constraint 'lip'", "point"}},
      {lip(R"("field": "u", "value": 0.5, "select": {)" + plane + R"(, "band": 0})"),
       {"constraint 'lip'", "band must be positive"}},
      {lip(R"("field": "u", "value": 0.5, "select": {)" + plane + R"(, "band": -1})"),
       {"constraint 'lip'", "band must be positive"}},
      {lip(R"("field": "u", "value": 0.5, "select": {)" + plane + R"(, "region": "sideways"})"),
       {"constraint 'lip'", "unknown region 'sideways'"}},
      {lip(R"("field": "u", "value": 0.5, "select": {)" + plane + R"(, "within": {"center": [0, 0, 0], "radius": 0}})"),
       {"constraint 'lip'", "within.radius must be positive"}},
      {lip(R"("field": "u", "value": 0.5, "select": {)" + plane + R"(, "within": {"center": [0, 0, 0]}})"),
       {"constraint 'lip'", "radius"}},
      {lip(R"("field": "u", "value": 0.5, "select": {)" + plane + R"(, "within": {"center": [0, 0], "radius": 3}})"),
       {"constraint 'lip'", "within.center must be an array of 3 numbers"}},
      {lip(R"("field": "u", "value": 0.5, "select": {)" + plane + R"(, "exclude": ["u0", "top"]})"),
       {"constraint 'lip'", "unknown side 'top' in exclude"}},
      // An unnamed constraint is named by its place in the list.
      {head + good + R"({"field": "w", "value": 1, "select": {"side": "w9"}}]})", {"constraint 'constraint 2'", "w9"}},
  };
  for (const auto& [text, words] : cases) {
    expect_error([&] { parse_constraint_set(text, "bad.json"); }, "bad.json", words);
    try {  // the JSON library's error codes stay out of the message
      parse_constraint_set(text, "bad.json");
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).find("[json.exception"), std::string::npos) << e.what();
    }
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Selecting vertices

TEST(SelectVertices, SidesAndIds) {
  const Cube cube;
  Selection top;
  top.side = V1;
  EXPECT_EQ(select_vertices(top, cube.V, cube.boundary, cube.mask), grid_ids([](int, int, int k) { return k == 2; }));
  Selection w0;
  w0.side = W0;
  EXPECT_EQ(select_vertices(w0, cube.V, cube.boundary, cube.mask), grid_ids([](int, int j, int) { return j == 0; }));
  Selection ids;
  ids.ids = {5, 2, 5, 26};  // sorted, once each; ids need no side_mask
  EXPECT_EQ(select_vertices(ids, cube.V, cube.boundary, Eigen::VectorXi()), (std::vector<int>{2, 5, 26}));
}

TEST(SelectVertices, PlaneBandRegionWithinAndExclude) {
  const Cube cube;
  const auto select = [&](const PlaneSelection& p) {
    return select_vertices(by_plane(p), cube.V, cube.boundary, cube.mask);
  };
  const auto mid_x = [](int i, int, int) { return i == 1; };
  EXPECT_EQ(select(plane_x(0.5, 0.2)), grid_ids(mid_x));   // the 9 vertices at x = 0.5
  EXPECT_EQ(select(plane_x(0.45, 0.2)), grid_ids(mid_x));  // 0.05 off the plane: within 0.1
  EXPECT_TRUE(select(plane_x(0.35, 0.2)).empty());         // 0.15 off: outside the band
  EXPECT_EQ(select(plane_x(0.5, 1.2)).size(), 27u);        // half-width 0.6 reaches x = 0 and 1
  EXPECT_EQ(select(plane_x(0.0, 1.2)), grid_ids([](int i, int, int) { return i <= 1; }));

  PlaneSelection boundary = plane_x(0.5, 0.2);
  boundary.region = "boundary";
  std::vector<int> expected = grid_ids(mid_x);
  expected.erase(std::find(expected.begin(), expected.end(), 13));  // the centre is inside
  EXPECT_EQ(select(boundary), expected);

  PlaneSelection on_w1 = plane_x(0.5, 0.2);
  on_w1.region = "w1";
  EXPECT_EQ(select(on_w1), (std::vector<int>{id(1, 2, 0), id(1, 2, 1), id(1, 2, 2)}));

  PlaneSelection within = plane_x(0.5, 0.2);
  within.within_center = Eigen::Vector3d(0.5, 0.5, 0.5);
  within.within_radius = 0.6;  // the centre and the four face centres (0.5 away), not the edge midpoints (0.71)
  EXPECT_EQ(select(within), (std::vector<int>{id(1, 1, 0), id(1, 0, 1), id(1, 1, 1), id(1, 2, 1), id(1, 1, 2)}));

  PlaneSelection exclude = plane_x(0.5, 0.2);
  exclude.exclude_sides = side_bit(V0) | side_bit(V1);  // a feature line stopping at the top and bottom cuts
  EXPECT_EQ(select(exclude), grid_ids([](int i, int, int k) { return i == 1 && k == 1; }));
}

TEST(SelectVertices, ATiltedPlaneFromAFileIsNormalized) {
  const Cube cube;
  // x + y = 1 with the normal written unnormalized: band 0.5 (half 0.25) takes the 9 vertices on the plane; the
  // nearest others are 0.5 / sqrt(2) = 0.35 away.
  const ConstraintSet set = parse_constraint_set(R"({"format": "facehex-constraints", "version": 1, "constraints": [
      {"field": "u", "value": 0.5,
       "select": {"plane": {"point": [0.5, 0.5, 0], "normal": [3, 3, 0]}, "band": 0.5}}]})",
                                                 "tilted.json");
  EXPECT_EQ(select_vertices(set.constraints[0].select, cube.V, cube.boundary, cube.mask),
            grid_ids([](int i, int j, int) { return i + j == 2; }));
}

TEST(SelectVertices, WithinSelectionLimits) {
  PlaneSelection p;
  const Eigen::Vector3d x(1, 2, 3);
  EXPECT_TRUE(within_selection_limits(p, x, false, 0));  // "volume": everything
  p.region = "boundary";
  EXPECT_FALSE(within_selection_limits(p, x, false, 0));
  EXPECT_TRUE(within_selection_limits(p, x, true, 0));
  p.region = "v0";
  EXPECT_FALSE(within_selection_limits(p, x, true, side_bit(V1)));
  EXPECT_TRUE(within_selection_limits(p, x, true, side_bit(V1) | side_bit(V0)));
  p.region = "volume";
  p.within_center = Eigen::Vector3d(1, 2, 5);
  p.within_radius = 2;
  EXPECT_TRUE(within_selection_limits(p, x, false, 0));  // at exactly the radius
  p.within_radius = 1.999;
  EXPECT_FALSE(within_selection_limits(p, x, false, 0));
  p.within_center.reset();
  p.exclude_sides = side_bit(U0) | side_bit(U1);
  EXPECT_FALSE(within_selection_limits(p, x, true, side_bit(U1) | side_bit(W1)));
  EXPECT_TRUE(within_selection_limits(p, x, true, side_bit(W1)));
}

TEST(SideMaskOf, ReadsTheArrayAsRoundedIntegersOrNothing) {
  VolumeMesh box = test::hex_box(1, 1, 1);
  const Eigen::VectorXi mask = side_mask_of(box);
  ASSERT_EQ(mask.size(), 8);
  EXPECT_EQ(mask(0), side_bit(U0) | side_bit(W0) | side_bit(V0));  // the corner at the origin
  EXPECT_EQ(mask(6), side_bit(U0) | side_bit(W1) | side_bit(V1));  // (0, 1, 1)
  EXPECT_EQ(mask(7), side_bit(U1) | side_bit(W1) | side_bit(V1));  // (1, 1, 1)
  box.point_data[kSideMaskArray](3, 0) = 5.0000001;
  EXPECT_EQ(side_mask_of(box)(3), 5);
  box.point_data.erase(kSideMaskArray);
  EXPECT_EQ(side_mask_of(box).size(), 0);
}

// ---------------------------------------------------------------------------------------------------------------
// Resolving a set on a model

TEST(ResolveConstraints, SideConstraintsPinEachFieldToItsCoordinate) {
  const ConstraintSet set = side_constraints();
  ASSERT_EQ(set.constraints.size(), 6u);
  for (int s = 0; s < kNumSides; ++s) {
    EXPECT_EQ(set.constraints[s].name, kSideDescriptions[s]);
    EXPECT_EQ(set.constraints[s].field, s / 2);
    EXPECT_EQ(set.constraints[s].value, s % 2);
    EXPECT_EQ(set.constraints[s].select.side, static_cast<Side>(s));
  }
  const Cube cube;
  const ResolvedConstraints r = resolve_constraints(set, cube.V, cube.T, cube.mask, "sides");
  ASSERT_EQ(r.selected.size(), 6u);
  for (int s = 0; s < kNumSides; ++s) EXPECT_EQ(r.selected[s].size(), 9u) << kSideNames[s];
  // u = x, v = z, w = y on the cube's faces (test_meshes.h).
  const int column[3] = {0, 2, 1};
  for (int f = 0; f < 3; ++f) {
    const DirichletConditions& bc = r.fields[f];
    ASSERT_EQ(bc.vertices.size(), 18u) << kFieldNames[f];
    ASSERT_EQ(bc.values.size(), 18u);
    EXPECT_TRUE(std::is_sorted(bc.vertices.begin(), bc.vertices.end()));
    for (size_t i = 0; i < bc.vertices.size(); ++i) EXPECT_EQ(bc.values[i], cube.V(bc.vertices[i], column[f]));
  }
}

TEST(ResolveConstraints, FeatureConstraintsAddTheirVerticesAndAgreeingOverlapsAreFine) {
  const Cube cube;
  ConstraintSet set = side_constraints();
  PlaneSelection mid = plane_x(0.5, 0.2);
  mid.exclude_sides = side_bit(U0) | side_bit(U1);
  set.constraints.push_back(constraint("mid-sagittal", 0, 0.5, by_plane(mid)));
  Selection corner;
  corner.ids = {0};  // on u0 already, with the same value
  set.constraints.push_back(constraint("corner", 0, 0.0, corner));
  const ResolvedConstraints r = resolve_constraints(set, cube.V, cube.T, cube.mask, "features");
  EXPECT_EQ(r.selected[6], grid_ids([](int i, int, int) { return i == 1; }));
  EXPECT_EQ(r.selected[7], std::vector<int>{0});
  ASSERT_EQ(r.fields[0].vertices.size(), 27u);  // every vertex now has its u, once
  for (size_t i = 0; i < 27; ++i) {
    EXPECT_EQ(r.fields[0].vertices[i], static_cast<int>(i));
    EXPECT_EQ(r.fields[0].values[i], cube.V(static_cast<int>(i), 0));
  }
  EXPECT_EQ(r.fields[1].vertices.size(), 18u);
  EXPECT_EQ(r.fields[2].vertices.size(), 18u);
}

TEST(ResolveConstraints, GeometricSelectionsNeedNoSideMask) {
  // The six ends as planes, without "side_mask": the same conditions as the side selections.
  const Cube cube;
  ConstraintSet set;
  const Eigen::Vector3d axis[3] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY()};
  for (int f = 0; f < 3; ++f)
    for (int end = 0; end < 2; ++end) {
      PlaneSelection p;
      p.point = end * axis[f];
      p.normal = axis[f];
      p.band = 0.2;
      p.region = "boundary";
      set.constraints.push_back(constraint(std::string(kFieldNames[f]) + std::to_string(end), f, end, by_plane(p)));
    }
  const ResolvedConstraints planes = resolve_constraints(set, cube.V, cube.T, Eigen::VectorXi(), "planes");
  const ResolvedConstraints sides = resolve_constraints(side_constraints(), cube.V, cube.T, cube.mask, "sides");
  for (int f = 0; f < 3; ++f) {
    EXPECT_EQ(planes.fields[f].vertices, sides.fields[f].vertices);
    EXPECT_EQ(planes.fields[f].values, sides.fields[f].values);
  }
}

TEST(ResolveConstraints, RejectsBadSetsNamingTheSourceAndTheConstraint) {
  const Cube cube;
  const auto resolve = [&](const ConstraintSet& set, const Eigen::VectorXi& mask) {
    return [&set, &mask, &cube] { resolve_constraints(set, cube.V, cube.T, mask, "face.json"); };
  };
  {
    ConstraintSet set = side_constraints();
    set.constraints.push_back(constraint("far plane", 0, 0.5, by_plane(plane_x(5, 1))));
    expect_error(resolve(set, cube.mask), "face.json", {"'far plane' selects no vertex"});
  }
  {
    ConstraintSet set = side_constraints();
    Selection corner;
    corner.ids = {id(0, 1, 1)};  // on u0 (u = 0)
    set.constraints.push_back(constraint("picked", 0, 0.25, corner));
    expect_error(resolve(set, cube.mask), "face.json",
                 {"vertex 12 gets two values in field u", "'lateral end at -x'", "'picked'"});
  }
  {
    ConstraintSet set = side_constraints();
    set.constraints.erase(set.constraints.begin() + U1);
    expect_error(resolve(set, cube.mask), "face.json", {"field u is missing its 1 end"});
  }
  {
    ConstraintSet set = side_constraints();
    set.constraints.erase(set.constraints.begin() + W0);
    expect_error(resolve(set, cube.mask), "face.json", {"field w is missing its 0 end"});
  }
  {
    ConstraintSet set = side_constraints();
    set.constraints.pop_back();
    set.constraints.push_back(constraint("skin at 0.99", 2, 0.99, side_constraints().constraints[W1].select));
    expect_error(resolve(set, cube.mask), "face.json", {"field w is missing its 1 end"});  // 1 exactly, not near
  }
  const Eigen::VectorXi no_mask;
  expect_error(resolve(side_constraints(), no_mask), "face.json", {"'lateral end at -x'", "\"side_mask\""});
  {
    ConstraintSet set = side_constraints();
    PlaneSelection on_w1 = plane_x(0.5, 0.2);
    on_w1.region = "w1";
    set.constraints[0] = constraint("region by side", 0, 0, by_plane(on_w1));
    expect_error(resolve(set, no_mask), "face.json", {"'region by side'", "\"side_mask\""});
    PlaneSelection excluding = plane_x(0.5, 0.2);
    excluding.exclude_sides = side_bit(V0);
    set.constraints[0] = constraint("excluding", 0, 0, by_plane(excluding));
    expect_error(resolve(set, no_mask), "face.json", {"'excluding'", "\"side_mask\""});
  }
  {
    ConstraintSet set = side_constraints();
    Selection ids;
    ids.ids = {3, 27};
    set.constraints.push_back(constraint("beyond", 1, 0.5, ids));
    expect_error(resolve(set, cube.mask), "face.json", {"'beyond'", "vertex id 27 is out of range"});
  }
}

// An empty "ids" list passes the parser ("ids" is present) but selects nothing: an Error naming the constraint, as for
// any selection that finds no vertex.
TEST(ResolveConstraints, AnEmptyIdListSelectsNoVertex) {
  const Cube cube;
  ConstraintSet set = side_constraints();
  set.constraints.push_back(constraint("nothing picked", 1, 0.5, Selection()));
  expect_error([&] { resolve_constraints(set, cube.V, cube.T, cube.mask, "face.json"); }, "face.json",
               {"'nothing picked' selects no vertex"});
}

}  // namespace
}  // namespace facehex
