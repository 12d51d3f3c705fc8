// `shadowbench merge OUT DIR...`: the shards of one run made one run folder.
#include <cstdio>

#include "cli/commands.h"
#include "core/error.h"
#include "results/merge.h"

namespace sb::cli {

using core::kExitOk;
using results::merge_runs;
using results::MergeOptions;
using results::MergeSummary;

int cmd_merge(const Args& a) {
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

}  // namespace sb::cli
