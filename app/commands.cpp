#include "app/commands.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <numeric>
#include <optional>
#include <set>
#include <sstream>

#include "app/cli_args.h"
#include "app/compare.h"
#include "app/output_folder.h"
#include "app/report.h"
#include "app/terminal_progress.h"
#include "app/transfer_command.h"
#include "core/face/automatic_constraints.h"
#include "core/fields/constraint_set.h"
#include "core/io/fe_sets.h"
#include "core/io/mesh_io.h"
#include "core/mapping/transfer_pipeline.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/shell_sides.h"
#include "core/mesh/sides.h"
#include "core/mesh/tet_topology.h"
#include "core/segment/patient_input.h"
#include "core/standard/closed_domain.h"
#include "core/standard/parameterization_cache.h"
#include "core/standard/template_mesh.h"
#include "core/util/error.h"
#include "core/util/resources.h"
#include "core/util/text_file.h"

namespace facehex::cli {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kForceExportHelp = "write .inp / .feb even if the mesh has inverted elements";

MeshWriteOptions write_options(const Args& args) {
  MeshWriteOptions o;
  o.allow_inverted = args.has("force-export");
  return o;
}

// "feb,inp,msh" -> {"feb", "inp", "msh"}, checked up front so that a typo does not cost a whole run.
std::vector<std::string> export_formats(const std::string& list) {
  std::vector<std::string> formats;
  std::stringstream in(list);
  const std::vector<std::string> writable = writable_volume_extensions();
  for (std::string f; std::getline(in, f, ',');) {
    if (f.empty()) continue;
    if (std::find(writable.begin(), writable.end(), "." + f) == writable.end())
      throw Error("--export", "cannot write '" + f + "' (use feb, inp, msh, vtk or vtu)");
    formats.push_back(f);
  }
  return formats;
}

void add_field_options(Args& args) {
  args.option("iterations", "orthogonality-improvement iterations (paper: 6)", "6")
      .option("order", "orthogonalization order: basic, second, third field (e.g. wuv)", "wuv");
}

void add_segment_options(Args& args) {
  args.option("skin", "skin threshold in the file's units (default: from the histogram)")
      .option("bone", "bone threshold in the file's units (default: from the histogram)")
      .option("anterior",
              "voxel axis the face looks to: +x -x +y -y +z -z (default: from a DICOM series' orientation, else +y)")
      .option("superior", "voxel axis towards the top of the head (default: from a DICOM series, else +z)")
      .option("top-cut",
              "height z (mm, segmentation frame) of the top cut (default: --face-height above the bottom cut)")
      .option("bottom-cut", "height z (mm) of the bottom cut (default: --chin-clearance below the chin's bone)")
      .option("posterior-cut", "y (mm) of the posterior cut (default: --ear-clearance in front of the ears)")
      .option("mid-plane", "x (mm) of the plane between the u0 and u1 ends (default: the head's mean x)")
      .option("face-height", "mm from the bottom to the top cut when --top-cut is not given", "130")
      .option("chin-clearance", "mm from the chin's bone down to the bottom cut", "10")
      .option("ear-clearance", "mm from the front of the ears forward to the posterior cut", "10");
}

// The constraint set of a model: the given file, else the six sides from its "side_mask".
ConstraintSet load_constraints(const std::string& path, const VolumeMesh& mesh, const std::string& mesh_path) {
  if (!path.empty()) return read_constraint_set(path);
  if (side_mask_of(mesh).size() == 0)
    throw Error(mesh_path, "no constraint set given and the model has no \"side_mask\" array (use --constraints)");
  return side_constraints();
}

void write_json(const std::string& path, const json& j) { write_text_file(path, j.dump(2) + "\n"); }

// How far the shape relaxation and the repair moved each vertex from where the harmonic mapping put it (mm), and
// each cell's mean dihedral-angle change against the standard (degrees; paper Table 1 per cell).
void attach_transfer_arrays(VolumeMesh& hex, const TransferRun& run, const VolumeMesh& standard) {
  hex.point_data["moved_from_mapping"] = moved_from_mapping(run);
  hex.cell_data["dihedral_change"] = cell_dihedral_change(standard, hex);
}

void attach_quality(VolumeMesh& mesh) {
  const ElementQuality q = element_quality(mesh);
  mesh.cell_data["shape"] = q.shape;
  mesh.cell_data["scaled_jacobian"] = q.scaled_jacobian;
}

// The fields of a parameterization at the mesh's vertices (the first rows of the parameterized domain).
void attach_fields(VolumeMesh& mesh, const ModelParameterization& p) {
  const Eigen::Index n = mesh.num_vertices();
  const Eigen::MatrixXd uvw = p.fields.uvw.topRows(n);
  mesh.point_data["u"] = uvw.col(0);
  mesh.point_data["v"] = uvw.col(1);
  mesh.point_data["w"] = uvw.col(2);
  mesh.point_data["uvw"] = uvw;
  mesh.point_data["uvw_initial"] = p.fields.uvw_initial.topRows(n);
  mesh.point_data["fixed_uvw"] = p.fixed.topRows(n).cast<double>();
}

// Writes the tet model with its fields and per-tet gradients (before/after) and gradient angles.
VolumeMesh parameterized_tet_mesh(const ModelParameterization& p, const VolumeMesh* source) {
  VolumeMesh m = VolumeMesh::from_tets(p.V, p.T);
  if (source && source->num_vertices() == p.V.rows()) m.point_data = source->point_data;  // same vertices
  attach_fields(m, p);
  for (int f = 0; f < 3; ++f) {
    m.cell_data[std::string("grad_") + kFieldNames[f]] = p.fields.gradients[f];
    m.cell_data[std::string("grad_") + kFieldNames[f] + "_initial"] = p.fields.gradients_initial[f];
  }
  return m;
}

// The per-tet gradients are there to be looked at (glyphs, angle histograms): as 32-bit floats they take half of what
// they take as doubles, most of a parameterized model's file.
MeshWriteOptions parameterized_model_writing() {
  MeshWriteOptions options;
  for (int f = 0; f < 3; ++f) {
    options.single_precision_arrays.insert(std::string("grad_") + kFieldNames[f]);
    options.single_precision_arrays.insert(std::string("grad_") + kFieldNames[f] + "_initial");
  }
  return options;
}

}  // namespace

HarmonicFieldsOptions field_options(const Args& args) {
  HarmonicFieldsOptions o;
  o.orthogonality_iterations = args.integer("iterations");
  const std::string order = args.get("order");
  if (order.size() != 3 || std::set<char>(order.begin(), order.end()) != std::set<char>{'u', 'v', 'w'})
    throw Error("--order", "expects a permutation of u, v, w such as wuv, got '" + order + "'");
  for (int i = 0; i < 3; ++i) o.order[i] = order[i] - 'u';
  return o;
}

TetDomain standard_domain(const VolumeMesh& hex, const std::string& kind) {
  if (kind == "closed") return closed_domain(hex);
  if (kind == "auxiliary") return auxiliary_domain(hex);
  throw Error("--standard-domain", "expects closed or auxiliary, got '" + kind + "'");
}

SegmentOptions segment_options(const Args& args) {
  SegmentOptions o;
  if (args.has("skin")) o.skin_threshold = args.number("skin");
  if (args.has("bone")) o.bone_threshold = args.number("bone");
  o.orientation.anterior = args.get("anterior");
  o.orientation.superior = args.get("superior");
  o.tets.target_edge_length = args.number("edge-length");
  const auto finite = [&](const std::string& name) {
    const double x = args.number(name);
    if (!std::isfinite(x))
      throw Error("--" + name, "expects a finite number of millimetres, got '" + args.get(name) + "'");
    return x;
  };
  const auto not_negative = [&](const std::string& name) {
    const double x = finite(name);
    if (x < 0) throw Error("--" + name, "expects a distance of 0 mm or more, got '" + args.get(name) + "'");
    return x;
  };
  FaceCutOptions& cuts = o.cuts;
  if (args.has("top-cut")) cuts.top_z = finite("top-cut");
  if (args.has("bottom-cut")) cuts.bottom_z = finite("bottom-cut");
  if (args.has("posterior-cut")) cuts.posterior_y = finite("posterior-cut");
  if (args.has("mid-plane")) cuts.centre_x = finite("mid-plane");
  cuts.face_height = not_negative("face-height");
  if (cuts.face_height == 0) throw Error("--face-height", "expects a height above 0 mm");
  cuts.chin_clearance = not_negative("chin-clearance");
  cuts.ear_clearance = not_negative("ear-clearance");
  return o;
}

VolumeMesh load_tet_model(const std::string& path, const SegmentOptions& options) {
  if (is_ct_input(path)) std::cerr << "segmenting the facial soft tissue from the CT " << path << "\n";
  TerminalProgress progress;  // the segmentation's steps (about 10 s for the bundled CT)
  PatientTetModel model = load_patient_model(path, options, progress.callback());
  progress.finish();
  if (model.segmentation)
    std::cerr << "segmentation: " << segmentation_summary(*model.segmentation)
              << "\n  (change with --skin, --bone, --top-cut, --bottom-cut, --posterior-cut, --mid-plane)\n";
  if (model.check.reoriented) std::cerr << "note: " << path << ": all tets were negatively oriented; flipped\n";
  return std::move(model.mesh);
}

struct TransferInputs {
  BundledModel standard;
  std::string standard_constraints;  // empty: the standard's bundled/sibling constraints
  std::string patient, patient_constraints;
  std::string standard_domain = "closed";
  SegmentOptions segment;
  TransferOptions options;
};

TransferOutputs execute_transfer(const TransferInputs& in) {
  TransferOutputs out;
  TerminalProgress progress;
  std::cerr << "reading the standard " << in.standard.mesh << "\n";
  out.standard = read_volume_mesh(in.standard.mesh);
  const std::string std_constraints =
      in.standard_constraints.empty() ? in.standard.constraints : in.standard_constraints;
  const ConstraintSet standard_set = read_constraint_set(std_constraints);
  std::cerr << "reading the patient " << in.patient << "\n";
  out.patient = load_tet_model(in.patient, in.segment);
  ConstraintSet patient_set = load_constraints(in.patient_constraints, out.patient, in.patient);
  if (in.patient_constraints.empty()) {
    // No set given: the sides plus feature constraints at the patient's landmarks, valued as the standard's.
    FaceLandmarks landmarks;
    patient_set = automatic_constraints(out.patient.V, side_mask_of(out.patient), feature_values(standard_set),
                                        kFeatureBand, &landmarks);
    std::cerr << "automatic constraints: six sides and " << feature_specs().size() << " features at the landmarks\n";
    std::cerr << landmarks_text(landmarks, "  ");
  }
  const TetDomain domain = standard_domain(out.standard, in.standard_domain);
  const std::string cache = parameterization_cache_path(in.standard.mesh);
  const std::optional<ModelParameterization> cached =
      cached_standard_parameterization(cache, domain, standard_set, in.options.fields);
  out.run = run_transfer(out.standard, domain, standard_set, std_constraints, out.patient, patient_set,
                         in.patient_constraints.empty() ? in.patient : in.patient_constraints, in.options,
                         progress.callback(), cached ? &*cached : nullptr);
  if (cached) out.run.standard_parameterization_source = cache;
  progress.finish();
  out.standard_quality = quality_report(out.standard, nullptr);
  out.plain_mapping_quality = quality_report(out.run.mapped_hex, &out.standard);
  out.patient_quality = quality_report(out.run.patient_hex, &out.standard);
  out.distance = side_vertex_distances(out.run, out.standard);
  return out;
}

std::optional<ModelParameterization> cached_standard_parameterization(const std::string& cache, const TetDomain& domain,
                                                                      const ConstraintSet& set,
                                                                      const HarmonicFieldsOptions& options) {
  std::string why_not;
  std::optional<ModelParameterization> cached = read_parameterization_cache(cache, domain, set, options, &why_not);
  if (!cached && !why_not.empty())
    std::cerr << "note: " << why_not << "; the standard's parameterization is computed instead (expected with "
              << "--standard-domain, --standard-constraints, --iterations or --order; after editing a bundled "
              << "standard, refresh it with facehex standards --write-cache)\n";
  return cached;
}

void add_transfer_options(Args& args) {
  args.option("standard", "bundled standard name or a hex mesh file", "artisynth-refface")
      .option("standard-constraints", "constraint set of the standard (default: the one bundled with it)")
      .option("edge-length", "target edge length (mm) when the patient is a closed surface or a CT", "2")
      .option("standard-domain",
              "tet domain of the standard: closed (openings filled) or auxiliary (paper: split hexes only)", "closed")
      .flag("allow-inverted", "continue even if the patient parameterization has inverted tets")
      .option("shape-relaxation",
              "after the mapping, move vertices along the patient towards the standard's cell shapes; where the "
              "mapping distorted a cell, its target moves this fraction of that distortion towards an ideal cell (0: "
              "the standard's own shapes); off: the paper's plain mapping",
              "0.5");
  add_field_options(args);
  add_segment_options(args);
}

TransferInputs transfer_inputs(const Args& args, const std::string& patient, const std::string& patient_constraints) {
  TransferInputs in;
  in.standard = find_standard(args.get("standard"));
  in.standard_constraints = args.get("standard-constraints");
  in.patient = patient;
  in.patient_constraints = patient_constraints;
  in.standard_domain = args.get("standard-domain");
  in.segment = segment_options(args);
  in.options.fields = field_options(args);
  in.options.allow_inverted_parameterization = args.has("allow-inverted");
  const std::string relaxation = args.get("shape-relaxation");
  in.options.shape_relaxation = relaxation != "off";
  if (in.options.shape_relaxation) {
    in.options.relaxation_towards_ideal = args.number("shape-relaxation");
    if (!(in.options.relaxation_towards_ideal >= 0 && in.options.relaxation_towards_ideal <= 1))
      throw Error("--shape-relaxation", "expects off or a fraction from 0 to 1, got '" + relaxation + "'");
  }
  return in;
}

TransferOutputs execute_transfer(const Args& args, const std::string& patient, const std::string& patient_constraints) {
  return execute_transfer(transfer_inputs(args, patient, patient_constraints));
}

int cmd_info(const Argv& argv) {
  Args args("info", "Prints sizes, cell types, bounding box, volume and side labels of a mesh.");
  args.positional("MESH", "mesh file");
  if (!args.parse(argv)) return 0;
  const std::string path = args.get("MESH");
  const VolumeMesh m = read_volume_mesh(path);
  const Eigen::RowVector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  std::cout << path << "\n  vertices " << m.num_vertices() << "\n  cells " << m.num_cells() << " (tet "
            << m.count(CellType::Tet) << ", wedge " << m.count(CellType::Wedge) << ", hex " << m.count(CellType::Hex)
            << ")\n  bounding box [" << lo << "] - [" << hi << "] mm\n";
  const Eigen::VectorXi mask = side_mask_of(m);
  if (mask.size() > 0) {
    std::cout << "  side vertices:";
    for (int s = 0; s < kNumSides; ++s)
      std::cout << " " << kSideNames[s] << " " << std::count_if(mask.data(), mask.data() + mask.size(), [&](int m) {
        return (m & side_bit(static_cast<Side>(s))) != 0;
      });
    std::cout << "\n";
  }
  std::cout << "  arrays:";
  for (const auto& [name, a] : m.point_data) std::cout << " " << name << "(point," << a.cols() << ")";
  for (const auto& [name, a] : m.cell_data) std::cout << " " << name << "(cell," << a.cols() << ")";
  std::cout << "\n";
  return 0;
}

int cmd_convert(const Argv& argv) {
  Args args("convert", "Converts a mesh to another format (a closed surface is tetrahedralized first).");
  args.positional("IN", "input mesh").positional("OUT", "output mesh (.vtu, .vtk, .msh, .inp, .feb)");
  args.option("edge-length", "target edge length (mm) for surfaces", "2").flag("force-export", kForceExportHelp);
  if (!args.parse(argv)) return 0;
  MeshReadOptions ro;
  ro.target_edge_length = args.number("edge-length");
  const VolumeMesh m = read_volume_mesh(args.get("IN"), ro);
  write_volume_mesh(args.get("OUT"), m, write_options(args));
  std::cout << "wrote " << args.get("OUT") << " (" << m.num_vertices() << " vertices, " << m.num_cells() << " cells)\n";
  return 0;
}

int cmd_sides(const Argv& argv) {
  Args args("sides",
            "Labels the six sides of a layered hex-dominant shell (a facial standard) from its element structure and "
            "writes it with the point-data array side_mask. Frame: +x lateral, +y anterior, +z superior.");
  args.positional("MESH", "hex-dominant mesh").option("output", "output .vtu");
  args.option("max-layers", "most element layers through the thickness", "8");
  if (!args.parse(argv)) return 0;
  if (!args.has("output")) throw Error("facehex sides", "missing -o OUTPUT");
  VolumeMesh m = read_volume_mesh(args.get("MESH"));
  ShellFrame frame = default_shell_frame(m.V);
  frame.max_layers = args.integer("max-layers");
  const ShellSides sides = label_shell_sides(m, frame);
  for (int s = 0; s < kNumSides; ++s)
    if (sides.faces_per_side[s] == 0)
      throw Error(args.get("MESH"), std::string("no boundary face found for side ") + kSideNames[s]);
  m.point_data[kSideMaskArray] = sides.side_mask.cast<double>();
  write_volume_mesh(args.get("output"), m);
  std::cout << "boundary faces per side:";
  for (int s = 0; s < kNumSides; ++s) std::cout << " " << kSideNames[s] << " " << sides.faces_per_side[s];
  std::cout << ", openings " << sides.opening_faces << "; vertices on opposite sides left free "
            << sides.conflicting_vertices << "\nwrote " << args.get("output") << "\n";
  return 0;
}

int cmd_fields(const Argv& argv) {
  Args args("fields",
            "Computes the three harmonic fields u, v, w of a model with its constraint set, improves their "
            "orthogonality, and writes the parameterized tet mesh (a hex mesh is split into its auxiliary tets).");
  args.positional("MODEL", "tet model, closed surface, or hex-dominant mesh")
      .option("constraints", "constraint-set JSON (default: the six sides from side_mask)")
      .option("output", "output .vtu")
      .option("edge-length", "target edge length (mm) when the model is a closed surface", "2")
      .option("standard-domain", "for a hex mesh: closed (openings filled) or auxiliary (split hexes only)", "closed");
  add_field_options(args);
  if (!args.parse(argv)) return 0;
  if (!args.has("output")) throw Error("facehex fields", "missing -o OUTPUT");
  const std::string path = args.get("MODEL");
  MeshReadOptions ro;
  ro.target_edge_length = args.number("edge-length");
  VolumeMesh mesh = read_volume_mesh(path, ro);
  TetDomain domain;
  if (mesh.is_tet_mesh()) {
    check_and_orient_tet_mesh(mesh, path);
    domain = {mesh.V, mesh.tets(), side_mask_of(mesh), mesh.num_vertices(), 0, "the model's own tets"};
  } else {
    domain = standard_domain(mesh, args.get("standard-domain"));
  }
  const ConstraintSet set = load_constraints(args.get("constraints"), mesh, path);
  TerminalProgress progress;
  const ModelParameterization p = parameterize_model(domain.V, domain.T, domain.side_mask, set,
                                                     args.has("constraints") ? args.get("constraints") : path,
                                                     field_options(args), progress.callback());
  progress.finish();
  VolumeMesh out = parameterized_tet_mesh(p, &mesh);
  if (domain.side_mask.size() == p.V.rows()) out.point_data[kSideMaskArray] = domain.side_mask.cast<double>();
  write_volume_mesh(args.get("output"), out, parameterized_model_writing());
  std::cout << "domain: " << domain.description << " (" << p.T.rows() << " tets)\n"
            << "parameterization: " << p.health.inverted << " inverted, "
            << (p.health.degenerate - p.health.flat_by_constraint) << " degenerate of " << p.health.tets << " tets\n"
            << "gradient angles, mean |90 - angle|: " << p.fields.angles_initial.mean_deviation_from_90
            << " deg before, " << p.fields.angles.mean_deviation_from_90 << " deg after\n"
            << "wrote " << args.get("output") << "\n";
  return p.health.ok() ? 0 : 3;
}

int cmd_map(const Argv& argv) {
  Args args("map",
            "Maps a standard hex mesh onto a patient tet model through their harmonic parameterizations "
            "(or, with --method mesh-matching, by the elastic-registration baseline of docs/method.md).");
  args.option("patient", "patient tet model or closed surface")
      .option("patient-constraints", "constraint set of the patient (default: six sides from side_mask)")
      .option("output", "output hex mesh (.vtu, .vtk, .msh)")
      .option("report", "write the JSON report here too")
      .option("method", "harmonic (the paper's method) or mesh-matching (the baseline it is compared with)",
              "harmonic");
  add_transfer_options(args);
  if (!args.parse(argv)) return 0;
  if (!args.has("patient") || !args.has("output")) throw Error("facehex map", "needs --patient and -o OUTPUT");
  if (args.get("method") == "mesh-matching") {
    const BundledModel standard = find_standard(args.get("standard"));
    MatchingOutputs out =
        execute_mesh_matching(read_volume_mesh(standard.mesh), standard.mesh,
                              load_tet_model(args.get("patient"), segment_options(args)), args.get("patient"));
    attach_quality(out.result.hex);
    write_volume_mesh(args.get("output"), out.result.hex);
    if (args.has("report")) write_json(args.get("report"), mesh_matching_report(out));
    std::cout << mesh_matching_summary_text(out) << "wrote " << args.get("output") << "\n";
    const QualitySummary& q = out.metrics.quality.summary;
    return q.inverted + q.degenerate == 0 ? 0 : 3;
  }
  if (args.get("method") != "harmonic")
    throw Error("--method", "expects harmonic or mesh-matching, got '" + args.get("method") + "'");
  TransferOutputs out = execute_transfer(transfer_inputs(args, args.get("patient"), args.get("patient-constraints")));
  attach_quality(out.run.patient_hex);
  attach_transfer_arrays(out.run.patient_hex, out.run, out.standard);
  write_volume_mesh(args.get("output"), out.run.patient_hex);
  if (args.has("report"))
    write_json(args.get("report"),
               run_report(out.run, out.standard_quality, out.plain_mapping_quality, out.patient_quality, out.distance));
  std::cout << run_summary_text(out.run, out.standard_quality, out.plain_mapping_quality, out.patient_quality,
                                out.distance)
            << "wrote " << args.get("output") << "\n";
  return 0;
}

int cmd_quality(const Argv& argv) {
  Args args("quality", "Element quality of a hex-dominant mesh; with --reference, the dihedral-angle distortion.");
  args.positional("MESH", "hex-dominant mesh")
      .option("reference", "the standard it was mapped from")
      .flag("json", "print JSON");
  if (!args.parse(argv)) return 0;
  const VolumeMesh m = read_volume_mesh(args.get("MESH"));
  VolumeMesh reference;
  if (args.has("reference")) reference = read_volume_mesh(args.get("reference"));
  const MeshQualityReport q = quality_report(m, args.has("reference") ? &reference : nullptr);
  if (args.has("json"))
    std::cout << to_json(q).dump(2) << "\n";
  else
    std::cout << args.get("MESH") << "\n" << quality_text(q);
  return q.summary.inverted + q.summary.degenerate == 0 ? 0 : 3;
}

int cmd_run(const Argv& argv) {
  Args args("run",
            "End to end: the patient (a CT is segmented first; default: the bundled sample CT) is parameterized with "
            "automatic constraints (or --constraints), the standard mapped onto it, and OUT/ gets patient_model.vtu, "
            "standard_hex.vtu, patient_hex.vtu and report.json.");
  args.positional("INPUT", "patient CT volume, tet model or closed surface", false)
      .option("output", "output folder")
      .option("constraints", "constraint set of the patient (default: bundled, or six sides from side_mask)")
      .option("export", "also write OUT/patient_hex.EXT for each listed format, e.g. feb,inp,msh (docs/export.md)")
      .flag("force-export", kForceExportHelp);
  add_transfer_options(args);
  if (!args.parse(argv)) return 0;
  if (!args.has("output")) throw Error("facehex run", "missing -o OUTPUT_FOLDER");
  const std::vector<std::string> exports = export_formats(args.get("export"));
  std::string input = args.get("INPUT"), constraints = args.get("constraints");
  if (input.empty()) {
    input = default_ct();
    std::cerr << "no input given: running the bundled demo, the whole chain from the sample CT " << input << "\n";
  }
  const TransferInputs inputs = transfer_inputs(args, input, constraints);  // option errors before any folder
  OutputFolder folder(args.get("output"));
  const fs::path& out_dir = folder.path();

  TransferOutputs out = execute_transfer(inputs);
  VolumeMesh patient_model = parameterized_tet_mesh(out.run.patient, &out.patient);
  VolumeMesh standard_hex = out.standard;
  attach_fields(standard_hex, out.run.standard);
  attach_quality(standard_hex);
  attach_quality(out.run.patient_hex);
  attach_transfer_arrays(out.run.patient_hex, out.run, out.standard);
  out.run.patient_hex.point_data["uvw"] = hex_vertex_uvw(out.run, out.standard.num_vertices());
  if (side_mask_of(out.standard).size() > 0)
    out.run.patient_hex.point_data[kSideMaskArray] = out.standard.point_data.at(kSideMaskArray);
  attach_fe_arrays(out.run.patient_hex);  // the FE sets and material frames, also in patient_hex.vtu

  write_volume_mesh((out_dir / "patient_model.vtu").string(), patient_model, parameterized_model_writing());
  write_volume_mesh((out_dir / "standard_hex.vtu").string(), standard_hex);
  write_volume_mesh((out_dir / "patient_hex.vtu").string(), out.run.patient_hex);
  json report = run_report(out.run, out.standard_quality, out.plain_mapping_quality, out.patient_quality, out.distance);
  report["inputs"] = {{"patient", input},
                      {"patient_constraints", constraints},
                      {"standard", out.standard.num_vertices() > 0 ? args.get("standard") : ""}};
  write_json((out_dir / "report.json").string(), report);
  std::cout << run_summary_text(out.run, out.standard_quality, out.plain_mapping_quality, out.patient_quality,
                                out.distance)
            << "outputs in " << out_dir.string()
            << "/: patient_model.vtu, standard_hex.vtu, patient_hex.vtu, report.json\n";
  for (const std::string& ext : exports) {
    write_volume_mesh((out_dir / ("patient_hex." + ext)).string(), out.run.patient_hex, write_options(args));
    std::cout << "exported " << (out_dir / ("patient_hex." + ext)).string() << "\n";
  }
  folder.keep();
  const QualitySummary& q = out.patient_quality.summary;
  if (q.inverted + q.degenerate > 0)
    std::cerr << "warning: " << q.inverted << " inverted and " << q.degenerate
              << " degenerate cells remain in patient_hex.vtu (cell data scaled_jacobian shows where)\n";
  return q.inverted + q.degenerate == 0 ? 0 : 3;
}

int cmd_segment(const Argv& argv) {
  Args args("segment",
            "From a head CT (MetaImage, NIfTI, NRRD, or a DICOM folder) to the labelled patient tet model of the "
            "facial soft tissue: thresholds from the histogram, cavities closed, cut at the forehead, below the chin "
            "and in front of the ears, six sides labelled (point data side_mask). See docs/segmentation.md.");
  args.positional("CT", "CT volume file or DICOM folder").option("output", "output tet model (.vtu)");
  args.option("edge-length", "target mean edge length of the tets (mm)", "2");
  add_segment_options(args);
  if (!args.parse(argv)) return 0;
  if (!args.has("output")) throw Error("facehex segment", "missing -o OUTPUT");
  const SegmentOptions options = segment_options(args);
  if (!is_ct_input(args.get("CT")))
    throw Error(args.get("CT"), "not a CT volume (.mhd, .mha, .nii, .nii.gz, .nrrd, or a DICOM folder)");
  const VolumeMesh model = load_tet_model(args.get("CT"), options);
  write_volume_mesh(args.get("output"), model);
  const Eigen::VectorXi mask = side_mask_of(model);
  std::cout << model.num_vertices() << " vertices, " << model.num_cells() << " tets; side vertices:";
  for (int s = 0; s < kNumSides; ++s)
    std::cout << " " << kSideNames[s] << " " << std::count_if(mask.data(), mask.data() + mask.size(), [&](int m) {
      return (m & side_bit(static_cast<Side>(s))) != 0;
    });
  std::cout << "\nwrote " << args.get("output") << "\n";
  return 0;
}

int cmd_constraints(const Argv& argv) {
  Args args("constraints",
            "Writes the constraint set of a model with side labels: its six sides and the feature constraints at its "
            "facial landmarks (mid-sagittal line, eyebrow, below-nose and middle lip lines). Feature values come "
            "from the standard's set, or with --own-values from this model's own harmonic fields (to build a "
            "standard's set). Landmark positions are printed for checking.");
  args.positional("MODEL", "tet model or hex-dominant standard with side_mask")
      .option("output", "output constraint-set JSON")
      .option("standard", "standard whose feature values to use", "artisynth-refface")
      .option("band", "slab width (mm) selecting feature vertices", "2")
      .flag("own-values", "take the feature values from the model's own fields (for a standard)");
  if (!args.parse(argv)) return 0;
  if (!args.has("output")) throw Error("facehex constraints", "missing -o OUTPUT");
  const std::string path = args.get("MODEL");
  const VolumeMesh mesh = read_volume_mesh(path);
  const Eigen::VectorXi mask = side_mask_of(mesh);
  std::map<std::string, double> values;
  FaceLandmarks landmarks;
  if (args.has("own-values")) {
    // Each feature's value is the mean of the model's side-only harmonic field over the vertices it selects.
    const TetDomain domain = mesh.is_tet_mesh() ? TetDomain{mesh.V, mesh.tets(), mask, mesh.num_vertices(), 0, ""}
                                                : standard_domain(mesh, "closed");
    HarmonicFieldsOptions plain;
    plain.orthogonality_iterations = 0;
    const ModelParameterization p =
        parameterize_model(domain.V, domain.T, domain.side_mask, side_constraints(), path, plain);
    std::map<std::string, double> placeholder;
    for (const auto& spec : feature_specs()) placeholder[spec.name] = 0.5;
    const ConstraintSet probe = automatic_constraints(mesh.V, mask, placeholder, args.number("band"), &landmarks);
    const std::vector<char> boundary =
        boundary_vertex_flags(static_cast<int>(domain.V.rows()), boundary_faces(domain.T).F);
    for (const auto& c : probe.constraints) {
      if (c.select.side) continue;
      const std::vector<int> sel = select_vertices(c.select, domain.V, boundary, domain.side_mask);
      if (sel.empty()) throw Error(path, "feature '" + c.name + "' selects no vertex");
      double sum = 0;
      for (int v : sel) sum += p.fields.uvw(v, c.field);
      values[c.name] = c.field == 0 ? 0.5 : sum / static_cast<double>(sel.size());
    }
  } else {
    values = feature_values(read_constraint_set(find_standard(args.get("standard")).constraints));
  }
  const ConstraintSet set = automatic_constraints(mesh.V, mask, values, args.number("band"), &landmarks);
  write_constraint_set(args.get("output"), set);
  std::cout << "mid-sagittal plane x = " << landmarks.x_mid << " mm\n";
  std::cout << landmarks_text(landmarks, "");
  for (const auto& c : set.constraints)
    if (!c.select.side) std::cout << c.name << ": " << kFieldNames[c.field] << " = " << c.value << "\n";
  std::cout << "wrote " << args.get("output") << "\n";
  return 0;
}

int cmd_template(const Argv& argv) {
  Args args("template",
            "Builds a new standard hex mesh from a reference model (paper 3.1): a grid in the reference's harmonic "
            "parameterization with rows on its feature lines, cells about --cell-size long along the face and "
            "--layers layers from bone to skin, mapped onto the reference and improved until no cell has a scaled "
            "Jacobian below --min-scaled-jacobian where that can be reached. OUT/ gets standard.vtu, constraints.json "
            "and README.md: a folder --standard accepts (or copy it to resources/standards/NAME/).");
  args.positional("REFERENCE", "reference CT volume, tet model or closed surface (default: the bundled sample CT)",
                  false)
      .option("output", "output folder")
      .option("constraints", "constraint set of the reference (default: sides + features at its landmarks)")
      .option("standard", "standard whose feature values the automatic constraints use", "artisynth-refface")
      .option("layers", "hex layers from bone to skin", "3")
      .option("cell-size", "cell length along the face (mm); 0: mean tissue thickness / layers", "0")
      .option("min-scaled-jacobian", "cells below this are improved by the untangler", "0.35")
      .option("edge-length", "target edge length (mm) when the reference is a closed surface or a CT", "2")
      .flag(
          "keep-sharp-corners",
          "keep every side vertex on the reference's surfaces, even where a sharp corner of the reference (a thin fin "
          "of tissue between a cut and the bone) leaves cells below --min-scaled-jacobian");
  add_field_options(args);
  add_segment_options(args);
  if (!args.parse(argv)) return 0;
  if (!args.has("output")) throw Error("facehex template", "missing -o OUTPUT_FOLDER");
  std::string input = args.get("REFERENCE");
  if (input.empty()) input = default_ct();
  OutputFolder folder(args.get("output"));
  const fs::path& out_dir = folder.path();

  const VolumeMesh reference = load_tet_model(input, segment_options(args));
  ConstraintSet reference_set;
  if (args.has("constraints")) {
    reference_set = read_constraint_set(args.get("constraints"));
  } else {
    FaceLandmarks landmarks;
    reference_set = automatic_constraints(
        reference.V, side_mask_of(reference),
        feature_values(read_constraint_set(find_standard(args.get("standard")).constraints)), kFeatureBand, &landmarks);
    std::cerr << "automatic constraints: six sides and " << feature_specs().size() << " features at the landmarks\n"
              << landmarks_text(landmarks, "  ");
  }
  TemplateOptions options;
  options.layers = args.integer("layers");
  options.cell_size = args.number("cell-size");
  options.cut_sharp_corners = !args.has("keep-sharp-corners");
  TransferOptions transfer;
  transfer.fields = field_options(args);
  transfer.untangle_options.min_scaled_jacobian = args.number("min-scaled-jacobian");
  TerminalProgress progress;
  TemplateResult t = build_template(reference, reference_set, input, options, transfer, progress.callback());
  progress.finish();

  const MeshQualityReport quality = quality_report(t.mesh, nullptr);
  const DistanceSummary off_surface = side_vertex_distances(t.mesh.V, t.mesh, reference.V, reference.tets());
  std::ostringstream fit;
  fit << "side vertices off the reference's surface: p95 " << fmt("%.2g", off_surface.p95) << " mm, max "
      << fmt("%.2g", off_surface.max) << " mm"
      << (options.cut_sharp_corners ? " (where the repair cut a sharp corner; --keep-sharp-corners keeps them on it)"
                                    : "")
      << "\n";
  VolumeMesh standard = t.mesh;
  attach_quality(standard);
  write_volume_mesh((out_dir / "standard.vtu").string(), standard);
  write_constraint_set((out_dir / "constraints.json").string(), t.constraints);
  std::ostringstream readme;
  readme << "# Template standard from " << fs::path(input).filename().string() << " (" << t.grid.cells(0) << " x "
         << t.grid.cells(1) << " x " << t.grid.cells(2) << " hexes, mean shape " << quality.summary.shape_mean
         << ")\n\nBuilt by `facehex template` (docs/method.md, template standards) from the reference " << input << " ("
         << reference.num_cells() << " tets; mean bone-to-skin thickness " << t.grid.mean_thickness << " mm), cells "
         << t.grid.cell_size << " mm along the face:\n\n    facehex template"
         << std::accumulate(argv.begin(), argv.end(), std::string(),
                            [](std::string a, const std::string& b) { return a + " " + b; })
         << "\n\n`constraints.json`: the six sides and the reference's feature lines as rows of the grid.\n\n"
         << "```\n"
         << quality_text(quality) << fit.str() << "```\n";
  write_text_file((out_dir / "README.md").string(), readme.str());
  folder.keep();
  std::cout << "grid " << t.grid.cells(0) << " x " << t.grid.cells(1) << " x " << t.grid.cells(2) << " = "
            << t.mesh.num_cells() << " hexes (cell size " << t.grid.cell_size << " mm, mean thickness "
            << t.grid.mean_thickness << " mm)\n"
            << "repair: " << t.run.untangle.bad_before << " cells below the bound before, " << t.run.untangle.bad_after
            << " after\n"
            << quality_text(quality) << fit.str() << "wrote " << out_dir.string()
            << "/: standard.vtu, constraints.json, README.md\n";
  const QualitySummary& q = quality.summary;
  return q.inverted + q.degenerate == 0 ? 0 : 3;
}

int cmd_standards(const Argv& argv) {
  Args args("standards",
            "Lists the bundled standard hex meshes (use a name with --standard). With --write-cache, computes each "
            "one's parameterization (closed domain, default field options) and keeps it beside it as "
            "standard.param.vtu + .json, which transfers then read instead of computing it.");
  args.flag("write-cache", "write the parameterization cache of every bundled standard");
  if (!args.parse(argv)) return 0;
  for (const auto& s : bundled_standards()) {
    std::cout << s.name << "\t" << s.description << "\n\t" << s.mesh << "\n";
    if (!args.has("write-cache")) continue;
    const VolumeMesh mesh = read_volume_mesh(s.mesh);
    const ConstraintSet set = read_constraint_set(s.constraints);
    const TetDomain domain = closed_domain(mesh);
    const HarmonicFieldsOptions options;
    const ModelParameterization p =
        parameterize_model(domain.V, domain.T, domain.side_mask, set, s.constraints, options);
    const std::string cache = parameterization_cache_path(s.mesh);
    write_parameterization_cache(cache, domain, p, set, options);
    std::cout << "\twrote " << cache << " (" << p.T.rows() << " tets, " << p.health.inverted
              << " folded in parameter space)\n";
  }
  return 0;
}

}  // namespace facehex::cli
