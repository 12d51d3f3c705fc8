// `shadowbench merge OUT DIR...`: the shards of one run made one run folder.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/command_line.h"
#include "cli/commands.h"
#include "cli/options.h"
#include "core/error.h"
#include "results/merge.h"

namespace sb::cli {

using core::kExitOk;
using results::merge_runs;
using results::MergeOptions;
using results::MergeSummary;

namespace {

struct MergeArgs {
  std::string out;
  std::vector<std::string> merge_dirs;
  bool allow_mixed_hosts = false;
};

int cmd_merge(const MergeArgs& a) {
  MergeOptions o;
  o.allow_mixed_hosts = a.allow_mixed_hosts;
  const MergeSummary s = merge_runs(a.out, a.merge_dirs, o);
  for (const std::string& w : s.warnings) std::fprintf(stderr, "merge: warning: %s\n", w.c_str());
  std::printf("merged %zu records and %zu images from %zu run folder%s into %s", s.records,
              s.images, a.merge_dirs.size(), a.merge_dirs.size() == 1 ? "" : "s", a.out.c_str());
  if (s.hosts.size() > 1)
    std::printf(" (timed on %zu hosts or GL renderers: the report marks them)", s.hosts.size());
  std::printf("\n");
  return kExitOk;
}

}  // namespace

void add_merge_command(CommandLine& cl) {
  const auto a = std::make_shared<MergeArgs>();
  CLI::App* merge = cl.add_command(
      cl.app(), "merge",
      "Merge the run folders of one config's shards into OUT: records, images and reports. "
      "Refuses timings from different hosts or GL renderers unless told.",
      "shadowbench merge results/sweep results/sweep-1 results/sweep-2",
      [a] { return cmd_merge(*a); });
  add_argument(merge, "OUT", a->out, "the merged run folder (new, or empty)")->required();
  add_argument(merge, "DIR", a->merge_dirs, "the run folders to merge")
      ->required()
      ->default_str("");
  merge->add_flag("--allow-mixed-hosts", a->allow_mixed_hosts,
                  "merge timings from different hosts or GL renderers; the report marks them");
}

}  // namespace sb::cli
