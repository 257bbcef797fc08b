#pragma once
// The patient tet model from whatever the user has: a head CT (segmented, soft_tissue.h), a tet mesh, or a closed
// surface (tetrahedralized at options.tets.target_edge_length), checked and positively oriented (mesh_check.h).
// `facehex run`, `facehex segment` and the desktop application's File > Open all start here.
#include "core/mesh.h"
#include "core/mesh_check.h"
#include "core/progress.h"
#include "core/segment/soft_tissue.h"

#include <string>

namespace facehex {

struct PatientTetModel {
  VolumeMesh mesh;     // positive tets; a segmented CT's has point data "side_mask"
  TetMeshCheck check;  // check.reoriented: the file's tets were all negatively oriented and have been flipped
};

// A CT is recognized by is_ct_input (ct_volume.h). Throws facehex::Error naming the file or the segmentation stage;
// `progress` hears of the segmentation's steps.
PatientTetModel load_patient_model(const std::string& path, const SegmentOptions& options = {},
                                   const ProgressCallback& progress = {});

}  // namespace facehex
