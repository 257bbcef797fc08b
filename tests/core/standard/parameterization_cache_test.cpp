// The standard's parameterization cache: a round trip gives what parameterize_model gives, and a cache made from
// anything else (mesh, constraints, options) or a damaged one is refused with a reason, never used.
#include "core/standard/parameterization_cache.h"

#include <gtest/gtest.h>

#include <fstream>

#include "core/mapping/transfer_pipeline.h"
#include "tests/core/io/io_test_util.h"
#include "tests/core/test_meshes.h"

namespace facehex {
namespace {

using test::TempDir;

struct CachedBox {
  VolumeMesh hex = test::hex_box(4, 2, 5, 40, 10, 50);
  TetDomain domain = auxiliary_domain(hex);
  ConstraintSet set = side_constraints();
  HarmonicFieldsOptions options;
  ModelParameterization computed() const {
    return parameterize_model(domain.V, domain.T, domain.side_mask, set, "box", options);
  }
};

TEST(ParameterizationCache, RoundTripGivesTheComputedParameterization) {
  TempDir dir;
  const CachedBox box;
  const ModelParameterization p = box.computed();
  const std::string path = parameterization_cache_path(dir.file("std.vtu"));
  EXPECT_EQ(path, dir.file("std.param.vtu"));
  write_parameterization_cache(path, box.domain, p, box.set, box.options);
  std::string why;
  const auto cached = read_parameterization_cache(path, box.domain, box.set, box.options, &why);
  ASSERT_TRUE(cached) << why;
  EXPECT_EQ(cached->fields.uvw, p.fields.uvw);  // bit for bit
  EXPECT_EQ(cached->fields.uvw_initial, p.fields.uvw_initial);
  EXPECT_EQ(cached->fixed, p.fixed);
  EXPECT_EQ(cached->health.orientation, p.health.orientation);
  EXPECT_EQ(cached->health.inverted, p.health.inverted);
  for (int f = 0; f < 3; ++f) EXPECT_LT((cached->fields.gradients[f] - p.fields.gradients[f]).norm(), 1e-12);
  EXPECT_NEAR(cached->fields.angles.mean_deviation_from_90, p.fields.angles.mean_deviation_from_90, 1e-12);

  // A transfer given the cached parameterization is the transfer that computes it.
  const VolumeMesh patient = VolumeMesh::from_tets(box.domain.V, box.domain.T);
  VolumeMesh labelled = patient;
  labelled.point_data[kSideMaskArray] = box.domain.side_mask.cast<double>();
  const TransferRun fresh =
      run_transfer(box.hex, box.domain, box.set, "box", labelled, box.set, "patient", TransferOptions{});
  const TransferRun given =
      run_transfer(box.hex, box.domain, box.set, "box", labelled, box.set, "patient", TransferOptions{}, {}, &*cached);
  EXPECT_EQ(given.standard_parameterization_source, "given");
  EXPECT_EQ(given.patient_hex.V, fresh.patient_hex.V);
}

TEST(ParameterizationCache, IsRefusedWhenMadeFromSomethingElseOrDamaged) {
  TempDir dir;
  const CachedBox box;
  const std::string path = dir.file("std.param.vtu");
  std::string why;
  EXPECT_FALSE(read_parameterization_cache(path, box.domain, box.set, box.options, &why));
  EXPECT_TRUE(why.empty());  // no cache at all: nothing to report

  write_parameterization_cache(path, box.domain, box.computed(), box.set, box.options);
  ConstraintSet other_set = box.set;
  other_set.constraints[0].value = 0.0;
  other_set.constraints.push_back({"middle", 0, 0.5, {}, ""});
  other_set.constraints.back().select.ids = {7};
  EXPECT_FALSE(read_parameterization_cache(path, box.domain, other_set, box.options, &why));
  EXPECT_NE(why.find("constraint set"), std::string::npos) << why;
  HarmonicFieldsOptions other_options;
  other_options.orthogonality_iterations = 2;
  EXPECT_FALSE(read_parameterization_cache(path, box.domain, box.set, other_options, &why));
  TetDomain moved = box.domain;
  moved.V(0, 0) += 1e-9;
  EXPECT_FALSE(read_parameterization_cache(path, moved, box.set, box.options, &why));
  EXPECT_NE(why.find("std.param.vtu"), std::string::npos) << why;

  std::ofstream(path, std::ios::trunc) << "<VTKFile";  // truncated mesh, intact fingerprint
  EXPECT_FALSE(read_parameterization_cache(path, box.domain, box.set, box.options, &why));
  EXPECT_NE(why.find("unreadable"), std::string::npos) << why;
}

}  // namespace
}  // namespace facehex
