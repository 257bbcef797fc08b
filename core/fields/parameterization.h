#pragma once
// A model's parameterization: its three harmonic fields under its resolved constraints (paper 3.2-3.3), the fixed
// flags and the parameterization's health. Made for the standard (on its tet domain) and for the patient alike.
#include <Eigen/Core>
#include <array>
#include <string>

#include "core/fields/constraint_set.h"
#include "core/fields/harmonic_fields.h"
#include "core/fields/param_health.h"
#include "core/util/progress.h"

namespace facehex {

// A model's parameterization: its tets (the patient's own, or the standard's auxiliary tets), the resolved
// constraints, the fields and their health.
struct ModelParameterization {
  Eigen::MatrixXd V;  // #V x 3
  Eigen::MatrixXi T;  // #T x 4
  ResolvedConstraints constraints;
  HarmonicFieldsResult fields;
  ParamHealth health;
  Eigen::MatrixXi fixed;  // #V x 3, nonzero where a field is fixed by a constraint
};

// added: further Dirichlet conditions per field (e.g. a dense correspondence on the skin), taken at the vertices the
// constraint set leaves free in that field.
using FieldConditions = std::array<DirichletConditions, 3>;
ModelParameterization parameterize_model(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                                         const Eigen::VectorXi& side_mask, const ConstraintSet& constraints,
                                         const std::string& source, const HarmonicFieldsOptions& options,
                                         const ProgressCallback& progress = {}, const FieldConditions* added = nullptr);

// The record of fields computed (or read back from a cache) for a model with its resolved constraints: the fixed
// flags, the fields clamped to the unit cube, the health. parameterize_model is this after HarmonicFields.
ModelParameterization parameterization_of(const Eigen::MatrixXd& V, const Eigen::MatrixXi& T,
                                          ResolvedConstraints constraints, HarmonicFieldsResult fields);

}  // namespace facehex
