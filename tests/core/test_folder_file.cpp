// core/folder_file: a path a folder names is opened inside it or not at all.
// The truth is the file system's: what each path names, made here.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "../common/scratch_folder.h"
#include "core/error.h"
#include "core/folder_file.h"

namespace sb {

using core::folder_path_problem;
using core::FolderFile;
using core::InputError;
using core::open_in_folder;

namespace {

namespace fs = std::filesystem;

using test::ScratchFolder;

void write_at(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

// The message open_in_folder refuses `rel` with ("" when it does not).
std::string refusal(const fs::path& folder, const std::string& rel) {
  try {
    (void)open_in_folder(folder.string(), rel);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(FolderFile, ARegularFileInsideIsReadWhole) {
  ScratchFolder f;
  write_at(f.path() / "run" / "jobs" / "a" / "shaded.png", "pixels");
  const std::optional<FolderFile> file =
      open_in_folder((f.path() / "run").string(), "jobs/a/shaded.png");
  ASSERT_TRUE(file.has_value());
  EXPECT_EQ(file->read_all(100), "pixels");
  EXPECT_EQ(file->path(), (f.path() / "run" / "jobs/a/shaded.png").string());
  EXPECT_THROW((void)file->read_all(3), InputError);  // over the cap
  EXPECT_TRUE(open_in_folder((f.path() / "run").string(), "./jobs//a/shaded.png").has_value());
}

TEST(FolderFile, AMissingFileIsNothingNotAnError) {
  ScratchFolder f;
  EXPECT_FALSE(open_in_folder(f.path().string(), "jobs/a/shaded.png").has_value());
  EXPECT_FALSE(open_in_folder((f.path() / "absent").string(), "results.jsonl").has_value());
}

TEST(FolderFile, AbsoluteAndDotDotPathsAreRefusedWithoutLookingAtThem) {
  ScratchFolder f;
  write_at(f.path() / "secret", "s");
  write_at(f.path() / "run" / "x", "x");
  const fs::path run = f.path() / "run";
  EXPECT_NE(refusal(run, (f.path() / "secret").string()).find("is absolute"), std::string::npos);
  EXPECT_NE(refusal(run, "../secret").find("'..'"), std::string::npos);
  EXPECT_NE(refusal(run, "jobs/../../secret").find("'..'"), std::string::npos);
  EXPECT_NE(refusal(run, "").find("empty"), std::string::npos);
  EXPECT_NE(refusal(run, std::string("x\0y", 3)).find("NUL"), std::string::npos);
  EXPECT_EQ(folder_path_problem("jobs/a/shaded.png"), "");
  EXPECT_NE(folder_path_problem("/etc/passwd"), "");
  EXPECT_NE(folder_path_problem(".."), "");
}

TEST(FolderFile, ASymbolicLinkIsRefusedWhereverItPoints) {
  ScratchFolder f;
  write_at(f.path() / "secret", "secret bytes");
  const fs::path run = f.path() / "run";
  write_at(run / "jobs" / "a" / "shaded.png", "pixels");
  fs::create_symlink(f.path() / "secret", run / "jobs" / "a" / "out.png");
  fs::create_symlink("/etc/passwd", run / "jobs" / "a" / "passwd.png");
  fs::create_symlink("shaded.png", run / "jobs" / "a" / "in.png");  // inside: still refused
  fs::create_symlink(f.path(), run / "up");                         // a folder link
  fs::create_symlink("jobs", run / "alias");                        // a folder link inside
  for (const char* rel : {"jobs/a/out.png", "jobs/a/passwd.png", "jobs/a/in.png", "up/secret",
                          "alias/a/shaded.png"}) {
    const std::string why = refusal(run, rel);
    EXPECT_NE(why.find("symbolic link"), std::string::npos) << rel << ": " << why;
    EXPECT_NE(why.find((run / rel).string()), std::string::npos) << why;  // names the file
  }
  // The folder itself is the caller's: a link to it is followed.
  fs::create_symlink(run, f.path() / "run-link");
  EXPECT_TRUE(open_in_folder((f.path() / "run-link").string(), "jobs/a/shaded.png").has_value());
}

TEST(FolderFile, AFifoOrAFolderIsRefusedWithoutWaiting) {
  ScratchFolder f;
  ASSERT_EQ(::mkfifo((f.path() / "fifo").c_str(), 0600), 0);
  fs::create_directories(f.path() / "dir");
  EXPECT_NE(refusal(f.path(), "fifo").find("not a regular file"), std::string::npos);
  EXPECT_NE(refusal(f.path(), "dir").find("not a regular file"), std::string::npos);
  write_at(f.path() / "file", "x");
  EXPECT_NE(refusal(f.path(), "file/x").find("not a folder"), std::string::npos);
}

}  // namespace sb
