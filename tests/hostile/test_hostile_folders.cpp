// Run folders from elsewhere: what report, merge
// and the image viewer read stays inside the folder a record names it from,
// and what they delete or replace is only what they made. Each case plants
// what a hostile folder would hold and checks the file system afterwards: a
// secret's bytes are not in the output, a foreign file is still there, byte
// for byte, and the command exits 2 naming it. No GL.
#include <gtest/gtest.h>
#include <openssl/evp.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../common/cli_run.h"
#include "../common/text.h"
#include "../report/report_fixture.h"
#include "metrics/image_io.h"
#include "results/html_report.h"
#include "results/image_viewer.h"
#include "store/results_store.h"

namespace sb {

// How a record reaches outside its run folder.
enum class Escape { Absolute, DotDot, SymlinkInside };

namespace {

namespace fs = std::filesystem;
using test::CliRun;
using test::has;
using test::read_text;

CliRun shadowbench(const std::string& args) {
  return test::run_command(std::string(SHADOWBENCH_EXE) + " " + args);
}

void write_text(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  test::write_text(p, text);
}

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

// A secret image outside the run folder: V = 0.8125 everywhere, a value no
// synthetic image holds. Its float plane, as the viewer's data files encode
// it (base64 of little-endian float32), is a 16-character string repeated.
constexpr float kSecretValue = 0.8125f;

std::string secret_base64() {
  const float three[3] = {kSecretValue, kSecretValue, kSecretValue};
  char out[17] = {};
  EVP_EncodeBlock(reinterpret_cast<unsigned char*>(out),
                  reinterpret_cast<const unsigned char*>(three), sizeof three);
  return out;
}

void write_secret(const fs::path& path, int w, int h) {
  core::ImageF img(w, h, 1);
  for (float& v : img.data) v = kSecretValue;
  metrics::io::write_exr(path.string(), img);
}

// Every file under `dir`, read whole.
std::string all_bytes_under(const fs::path& dir) {
  std::string all;
  if (!fs::exists(dir)) return all;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) all += read_text(e.path());
  return all;
}

// The synthetic run with its records in results.jsonl (as a run writes it).
test::SyntheticRun stored_run(const fs::path& root) {
  test::SyntheticRun run = test::make_synthetic_run(root);
  store::ResultsStore(run.run_dir.string()).put_all(run.records);
  return run;
}

std::string escape_name(const ::testing::TestParamInfo<Escape>& p) {
  switch (p.param) {
    case Escape::Absolute:
      return "Absolute";
    case Escape::DotDot:
      return "DotDot";
    default:
      return "SymlinkInside";
  }
}

}  // namespace

class ViewerReads : public ::testing::TestWithParam<Escape> {};

// A record of the first job names, or its folder holds through a link, an
// EXR outside the run folder: the viewer's data files hold none of its bytes.
// The same file put inside the folder is shown: the check can see it.
TEST_P(ViewerReads, AnImageOutsideTheRunFolderNeverReachesTheViewerData) {
  const fs::path root = test::test_folder("sb_hostile_viewer_");
  test::SyntheticRun run = test::make_synthetic_run(root);
  record::JobRecord& r = run.records[0];  // "none" at 64x48
  write_secret(root / "secret.exr", r.width, r.height);
  switch (GetParam()) {
    case Escape::Absolute:
      r.images.visibility = (root / "secret.exr").string();
      break;
    case Escape::DotDot:
      r.images.visibility = "../secret.exr";
      break;
    case Escape::SymlinkInside:
      fs::remove(run.run_dir / *r.images.visibility);
      fs::create_symlink(root / "secret.exr", run.run_dir / *r.images.visibility);
      break;
  }
  results::write_html_report(run.records, run.run_dir.string(), run.out_dir.string(), run.charts,
                             "hostile");
  const std::string secret = secret_base64();
  const std::string data = all_bytes_under(run.out_dir / results::kViewerDataDir);
  EXPECT_FALSE(data.empty());  // the other jobs' data are there
  EXPECT_FALSE(has(data, secret)) << "the secret image reached the viewer's data";
  EXPECT_FALSE(has(read_text(run.out_dir / "index.html"), secret));

  // Control: the same image as a regular file inside the folder is shown.
  const std::string inside = "jobs/" + r.job_id + "/visibility.exr";
  fs::remove(run.run_dir / inside);
  fs::copy_file(root / "secret.exr", run.run_dir / inside);
  r.images.visibility = inside;
  results::write_html_report(run.records, run.run_dir.string(), run.out_dir.string(), run.charts,
                             "control");
  EXPECT_TRUE(has(all_bytes_under(run.out_dir / results::kViewerDataDir), secret));
}

INSTANTIATE_TEST_SUITE_P(HostileFolders, ViewerReads,
                         ::testing::Values(Escape::Absolute, Escape::DotDot, Escape::SymlinkInside),
                         escape_name);

// A file of the user's in the report's viewer folder: report exits 2 naming
// it and keeps it, with the viewer's data or without.
TEST(HostileFolders, ReportKeepsAForeignFileInItsViewerFolderAndSaysSo) {
  const fs::path root = test::test_folder("sb_hostile_report_viewer_");
  const test::SyntheticRun run = stored_run(root);
  const fs::path out = root / "out";
  const fs::path notes = out / results::kViewerDataDir / "notes.txt";
  write_text(notes, "my notes\n");
  for (const char* flag : {"", " --no-viewer-data"}) {
    const CliRun report = shadowbench("report " + q(run.run_dir) + " --out " + q(out) + flag);
    EXPECT_EQ(report.exit_code, 2) << flag << report.output;
    EXPECT_TRUE(has(report.output, notes.string())) << report.output;
    ASSERT_TRUE(fs::exists(notes)) << flag;
    EXPECT_EQ(read_text(notes), "my notes\n");
  }
  // A viewer that is a link to a folder of the user's: kept, and refused.
  const fs::path mine = root / "mine";
  write_text(mine / "0-0.js", "precious\n");
  fs::remove_all(out / results::kViewerDataDir);
  fs::create_symlink(mine, out / results::kViewerDataDir);
  const CliRun linked = shadowbench("report " + q(run.run_dir) + " --out " + q(out));
  EXPECT_EQ(linked.exit_code, 2) << linked.output;
  EXPECT_EQ(read_text(mine / "0-0.js"), "precious\n");
}

// The report's own viewer folder (its marker) is replaced by the next report.
TEST(HostileFolders, TheReportsOwnViewerFolderIsReplaced) {
  const fs::path root = test::test_folder("sb_hostile_own_viewer_");
  const test::SyntheticRun run = test::make_synthetic_run(root);
  test::write_synthetic_report(run);
  const fs::path viewer = run.out_dir / results::kViewerDataDir;
  EXPECT_TRUE(fs::is_regular_file(viewer / results::kViewerMarkerFile));
  write_text(viewer / "9-9.js", "stale\n");
  results::write_html_report(run.records, run.run_dir.string(), run.out_dir.string(), run.charts,
                             "again", false);
  EXPECT_FALSE(fs::exists(viewer));
}

// A shard's image that links to /etc/passwd: merge exits 2 naming it, and no
// merged file holds the linked file's bytes.
TEST(HostileFolders, MergeCopiesNoImageThroughASymbolicLink) {
  const fs::path root = test::test_folder("sb_hostile_merge_link_");
  const test::SyntheticRun run = stored_run(root);
  const fs::path shaded = run.run_dir / *run.records[0].images.shaded;
  fs::remove(shaded);
  fs::create_symlink("/etc/passwd", shaded);
  const CliRun merge = shadowbench("merge " + q(root / "merged") + " " + q(run.run_dir));
  EXPECT_EQ(merge.exit_code, 2) << merge.output;
  EXPECT_TRUE(has(merge.output, shaded.string())) << merge.output;
  EXPECT_TRUE(has(merge.output, "symbolic link")) << merge.output;
  const std::string passwd = read_text("/etc/passwd");
  ASSERT_FALSE(passwd.empty());
  EXPECT_FALSE(has(all_bytes_under(root / "merged"), passwd));
}

// Records naming an image by an absolute or a "../" path: refused, nothing
// copied.
TEST(HostileFolders, MergeRefusesImagesOutsideTheRunFolder) {
  for (const std::string& bad : {std::string("/etc/passwd"), std::string("../../../etc/passwd")}) {
    const fs::path root = test::test_folder("sb_hostile_merge_outside_");
    test::SyntheticRun run = test::make_synthetic_run(root);
    run.records[0].images.shaded = bad;
    store::ResultsStore(run.run_dir.string()).put_all(run.records);
    const CliRun merge = shadowbench("merge " + q(root / "merged") + " " + q(run.run_dir));
    EXPECT_EQ(merge.exit_code, 2) << bad << merge.output;
    EXPECT_TRUE(has(merge.output, "outside its run folder")) << merge.output;
    EXPECT_FALSE(has(all_bytes_under(root / "merged"), read_text("/etc/passwd")));
  }
}

// An OUT that holds files merge did not make: exit 2 naming one, all kept.
TEST(HostileFolders, MergeKeepsAForeignPlanAndSummaryInOut) {
  const fs::path root = test::test_folder("sb_hostile_merge_out_");
  const test::SyntheticRun run = stored_run(root);
  const fs::path out = root / "out";
  write_text(out / "plan.json", "{\"mine\": true}\n");
  write_text(out / "summary.md", "# my summary\n");
  const CliRun merge = shadowbench("merge " + q(out) + " " + q(run.run_dir));
  EXPECT_EQ(merge.exit_code, 2) << merge.output;
  EXPECT_TRUE(has(merge.output, (out / "plan.json").string()) ||
              has(merge.output, (out / "summary.md").string()))
      << merge.output;
  EXPECT_EQ(read_text(out / "plan.json"), "{\"mine\": true}\n");
  EXPECT_EQ(read_text(out / "summary.md"), "# my summary\n");
  EXPECT_FALSE(fs::exists(out / "results.jsonl"));

  // An empty folder is merged into, and marked as merge's.
  const fs::path empty = root / "empty";
  fs::create_directories(empty);
  const CliRun into_empty = shadowbench("merge " + q(empty) + " " + q(run.run_dir));
  EXPECT_EQ(into_empty.exit_code, 0) << into_empty.output;
  EXPECT_TRUE(fs::is_regular_file(empty / ".shadowbench-merge"));
  EXPECT_TRUE(fs::is_regular_file(empty / *run.records[0].images.shaded));
}

}  // namespace sb
