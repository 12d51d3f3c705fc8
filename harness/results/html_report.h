#pragma once
// The HTML report of a run (index.html in the report folder): the summary
// tables (sortable), the charts and an image grid per scene variant and
// resolution (reference, each technique's shaded image and error heat map,
// with a colour legend). It works offline from the file system: inline CSS
// and JS, no network, images linked by paths relative to the report folder.
#include <string>
#include <vector>

#include "record/job_record.h"

namespace sb::results {

// A chart made by the caller. Paths are relative to out_dir; an absolute one,
// or one relative to the working directory that names an existing file (as
// write_charts returns them), is made relative to out_dir.
struct ReportChart {
  std::string title;
  std::string svg;  // shown (as <img>); the PNG when empty
  std::string png;  // linked from the chart
};

// The legend image written next to index.html: the heat-map colour ramp
// (metrics::heatmap_colour) from 0 on the left to full scale on the right.
inline constexpr const char* kHeatmapLegendFile = "heatmap_legend.png";

// Writes out_dir/index.html (atomically) and out_dir/heatmap_legend.png,
// creating out_dir. Its summary tables have the columns of results.csv
// (results/report_columns.h). Images named by the records (paths relative to
// run_dir) are linked relative to out_dir, not copied. After loading, the
// page's script sets <body data-images-ok="true|false" data-missing="...">
// and logs console.error for each image that did not load. Each group gets an
// interactive viewer (results/image_viewer.h) whose data files go to
// out_dir/viewer, unless viewer_data is false. out_dir/viewer is replaced
// (with or without viewer_data) only when it is the report's own:
// check_viewer_folder.
void write_html_report(const std::vector<record::JobRecord>& records, const std::string& run_dir,
                       const std::string& out_dir, const std::vector<ReportChart>& charts,
                       const std::string& title, bool viewer_data = true);

// The file that marks a viewer folder as the report's (written first into
// out_dir/viewer).
inline constexpr const char* kViewerMarkerFile = ".shadowbench-viewer";

// Throws InputError naming what stops out_dir/viewer from being replaced:
// the folder may go when it is not there, or holds the marker file, or
// (written before the marker) only the viewer's data files "<n>-<m>.js";
// anything else there (a file of the user's, a symbolic link, a viewer that
// is not a folder) is kept and named. docs/robustness.md.
void check_viewer_folder(const std::string& out_dir);

}  // namespace sb::results
