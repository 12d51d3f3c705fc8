#pragma once
// The report's interactive image comparison: one viewer per scene variant and
// resolution holding the reference and every technique. Keys 1-9 and the
// arrows flip between them, a split line compares two, the wheel zooms to
// the pixel (nearest neighbour), and the pixel under the cursor is read out:
// V, the reference's V, |V - V_ref| and the reference's standard error σ.
// It shows the shaded image, V, the error heat map or the FLIP map, with an
// exposure for the two drawn from the EXRs (V and error).
//
// Pages opened from the file system cannot read an image's pixels (Chromium
// treats every file as its own origin, and a canvas holding another origin's
// image refuses getImageData), so the values come from data files written
// beside the report: viewer/<viewer>-<item>.js, each V (and the reference's
// σ) as base64 float32, loaded as a <script> when an item is first shown.
#include <filesystem>
#include <string>
#include <vector>

#include "record/job_record.h"

namespace sb::results {

struct ViewerGroup {
  int index = 0;                               // names its data files
  std::string title;                           // scene variant @ resolution
  std::vector<const record::JobRecord*> jobs;  // in the summary table's order
};

// The folder of the viewers' data files, relative to the report.
inline constexpr const char* kViewerDataDir = "viewer";

// Writes the group's data files into out_dir/viewer (the EXRs the records name,
// read from run_dir; an item whose EXR is missing has no data, and its V and
// error modes say so) and returns the viewer's markup. run_from_out is the run
// folder relative to out_dir, for the image URLs. With write_data false, no
// file is written and the viewer shows the PNGs only.
std::string image_viewer(const ViewerGroup& group, const std::filesystem::path& run_dir,
                         const std::filesystem::path& out_dir,
                         const std::filesystem::path& run_from_out, bool write_data);

// The viewer's style sheet and script, once per page (after page_style and
// page_script). The script drives every <section class="viewer"> and sets,
// on each, data-state="ready" once the data its items need have loaded.
const char* image_viewer_style();
const char* image_viewer_script();

}  // namespace sb::results
