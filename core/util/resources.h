#pragma once
// The bundled data under resources/ (standards, sample patients). The folder is the source tree's resources/
// (compiled in), unless the environment variable FACEHEX_RESOURCES names another one.
//
// Layout: resources/standards/NAME/{standard.vtu, constraints.json, README.md}
//         resources/patients/NAME/{patient.vtu, constraints.json}
//         resources/ct/NAME/NAME.mhd (+ .raw)
#include <string>
#include <vector>

namespace facehex {

std::string resource_dir();

struct BundledModel {
  std::string name;
  std::string mesh;         // path of the mesh file
  std::string constraints;  // path of its constraint-set JSON
  std::string description;  // first line of its README.md, if any
};

std::vector<BundledModel> bundled_standards();
std::vector<BundledModel> bundled_patients();

// The constraint file that goes with a model file: NAME.json beside it, else constraints.json in its folder (the
// bundled models' layout); empty when there is none.
std::string constraints_beside(const std::string& model_path);

// A bundled standard by name, or a mesh path (its constraints: constraints_beside it). Throws facehex::Error when
// neither exists.
BundledModel find_standard(const std::string& name_or_path);
BundledModel default_standard();
BundledModel default_patient();
// The bundled sample CT (resources/ct/headsq/headsq.mhd).
std::string default_ct();

}  // namespace facehex
