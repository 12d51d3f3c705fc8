// core/atomic_file: a file appears whole under its name or not at all,
// nothing is left behind that store/results_store.cpp would not recognise, no
// write goes through a symlink planted in the folder, and
// a failed write names the reason (item 11).
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "../common/scratch_folder.h"
#include "core/atomic_file.h"
#include "core/error.h"

namespace sb {

using core::AtomicFile;
using core::is_atomic_temp_name;
using core::JobError;
using core::write_file_atomically;

namespace {

namespace fs = std::filesystem;

// A scratch folder that lists what it holds.
class Folder : public test::ScratchFolder {
 public:
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(path())) out.push_back(e.path().filename());
    return out;
  }
};

std::string read_back(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(core_atomic_file, WritesThenReadsBackAndReplaces) {
  Folder dir;
  const std::string path = (dir / "out.bin").string();
  const std::string first("a\0b\r\n", 5);  // binary: no newline translation, NUL kept
  write_file_atomically(path, first);
  EXPECT_EQ(read_back(path), first);
  write_file_atomically(path, "shorter");
  EXPECT_EQ(read_back(path), "shorter");
  EXPECT_EQ(dir.names(), std::vector<std::string>{"out.bin"});
}

TEST(core_atomic_file, FailedWriteNamesThePathAndLeavesNothing) {
  Folder dir;
  const std::string path = (dir / "missing" / "out.bin").string();
  try {
    write_file_atomically(path, "x", "reference cache: ");
    FAIL() << "wrote into a folder that does not exist";
  } catch (const JobError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("reference cache: cannot write ", 0), 0u) << what;
    EXPECT_NE(what.find(path), std::string::npos) << what;
  }
  EXPECT_TRUE(dir.names().empty());
}

TEST(core_atomic_file, FailedRenameNamesThePathAndLeavesNoTemporaryFile) {
  Folder dir;
  // A non-empty folder under the final name: the rename cannot replace it.
  fs::create_directories(dir / "out.bin" / "inside");
  const std::string path = (dir / "out.bin").string();
  try {
    write_file_atomically(path, "x");
    FAIL() << "replaced a folder";
  } catch (const JobError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("cannot rename ", 0), 0u) << what;
    EXPECT_NE(what.find(" to " + path + ": "), std::string::npos) << what;
  }
  EXPECT_EQ(dir.names(), std::vector<std::string>{"out.bin"});
}

TEST(core_atomic_file, UncommittedFileLeavesNoFileAndNoTemporaryFile) {
  Folder dir;
  const std::string path = (dir / "image.exr").string();
  {
    AtomicFile file(path);
    std::ofstream(file.temp_path()) << "half an image";
    ASSERT_TRUE(fs::exists(file.temp_path()));
    EXPECT_EQ(fs::path(file.temp_path()).parent_path(), fs::path(path).parent_path());
  }
  EXPECT_TRUE(dir.names().empty());
}

TEST(core_atomic_file, CommitPutsTheTemporaryFileInPlace) {
  Folder dir;
  const std::string path = (dir / "image.exr").string();
  {
    AtomicFile file(path);
    std::ofstream(file.temp_path()) << "pixels";
    file.commit();
  }
  EXPECT_EQ(read_back(path), "pixels");
  EXPECT_EQ(dir.names(), std::vector<std::string>{"image.exr"});
}

TEST(core_atomic_file, TemporaryNamesAreRecognisedAndFinalNamesAreNot) {
  Folder dir;
  const std::string path = (dir / "job.json").string();
  const AtomicFile a(path), b(path);
  EXPECT_NE(a.temp_path(), b.temp_path());  // two writers of one path
  for (const AtomicFile* f : {&a, &b}) {
    const std::string name = fs::path(f->temp_path()).filename();
    EXPECT_EQ(name.rfind("job.json.tmp-" + std::to_string(::getpid()) + "-", 0), 0u) << name;
    EXPECT_TRUE(is_atomic_temp_name(name)) << name;
  }
  EXPECT_TRUE(is_atomic_temp_name("job.json.tmp-4242"));  // an earlier version's
  for (const char* final_name : {"job.json", "results.jsonl", "a.tmp-1.json", "a.tmp-", "a.tmp-x",
                                 "a.tmp-1-", "a.tmp-1-2x", ".tmp-1", "key.sbref", "key.lock"})
    EXPECT_FALSE(is_atomic_temp_name(final_name)) << final_name;
}

// What a hostile run folder holds: a symlink at the target and at every
// temporary name this process would try first, all pointing at one file
// outside the folder.
struct PlantedFolder {
  Folder dir, outside;
  std::string target, victim;
  static constexpr const char* kVictim = "# the user's own file\n";
  explicit PlantedFolder(const std::string& name) {
    target = (dir / name).string();
    victim = (outside / "bashrc").string();
    std::ofstream(victim, std::ios::binary) << kVictim;
    fs::create_symlink(victim, target);
    // Earlier versions' "<name>.tmp-<pid>" and this version's counters.
    fs::create_symlink(victim, target + ".tmp-" + std::to_string(::getpid()));
    for (int n = 0; n < 512; ++n)
      fs::create_symlink(victim,
                         target + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(n));
  }
};

TEST(core_atomic_file, PlantedSymlinksAreReplacedNeverWrittenThrough) {
  PlantedFolder f("results.csv");
  write_file_atomically(f.target, "label\n$(touch PWNED)\n");
  EXPECT_EQ(read_back(f.victim), PlantedFolder::kVictim);
  EXPECT_EQ(fs::symlink_status(f.target).type(), fs::file_type::regular);
  EXPECT_EQ(read_back(f.target), "label\n$(touch PWNED)\n");
  size_t left = 0;  // the planted temporary names are still symlinks; nothing else appeared
  for (const std::string& name : f.dir.names())
    if (name != "results.csv") {
      EXPECT_EQ(fs::symlink_status(f.dir / name).type(), fs::file_type::symlink) << name;
      ++left;
    }
  EXPECT_EQ(left, 513u);
}

TEST(core_atomic_file, FileNameWritersGetAFileOfTheirOwnNotAPlantedSymlink) {
  PlantedFolder f("image.png");
  {
    AtomicFile file(f.target);
    EXPECT_EQ(fs::symlink_status(file.temp_path()).type(), fs::file_type::regular);
    std::ofstream(file.temp_path(), std::ios::binary) << "pixels";  // as OpenImageIO does
    file.commit();
  }
  EXPECT_EQ(read_back(f.victim), PlantedFolder::kVictim);
  EXPECT_EQ(fs::symlink_status(f.target).type(), fs::file_type::regular);
  EXPECT_EQ(read_back(f.target), "pixels");
}

// The reason, in strerror's words, for a write that the kernel refuses: a
// file-size limit (any user; "File too large") stands for the full disk.
TEST(core_atomic_file, FailedWriteNamesTheReason) {
  Folder dir;
  const std::string path = (dir / "results.csv").string();
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = old;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  std::string what;
  try {
    write_file_atomically(path, std::string(100000, 'x'), "report: ");
  } catch (const JobError& e) {
    what = e.what();
  }
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_EQ(what.rfind("report: cannot write " + path + ".tmp-", 0), 0u) << what;
  EXPECT_NE(what.find(": File too large"), std::string::npos) << what;
  EXPECT_TRUE(dir.names().empty());
}

// A full file system: a 64 KiB tmpfs mounted on a test folder (root only;
// skipped elsewhere, where FailedWriteNamesTheReason stands for it).
TEST(core_atomic_file, FullFileSystemIsNamed) {
  Folder dir;
  const std::string mnt = (dir / "small").string();
  fs::create_directories(mnt);
  if (::geteuid() != 0 || ::mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=64k") != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here (not root)";
  struct Unmount {
    std::string at;
    ~Unmount() { ::umount2(at.c_str(), MNT_DETACH); }
  } unmount{mnt};
  const std::string path = mnt + "/results.csv";
  try {
    write_file_atomically(path, std::string(1 << 20, 'x'));
    FAIL() << "wrote 1 MiB into 64 KiB";
  } catch (const JobError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(": No space left on device"), std::string::npos) << what;
  }
  EXPECT_TRUE(fs::is_empty(mnt));
}

TEST(core_atomic_file, OwnFoldersAreNeverReachedThroughASymlink) {
  Folder dir, outside;
  core::make_own_folder(dir / "run", "jobs/a");
  EXPECT_TRUE(fs::is_directory(fs::symlink_status(dir / "run" / "jobs" / "a")));
  fs::create_symlink(outside / ".", dir / "run" / "report");
  fs::create_symlink(outside / ".", dir / "run" / "jobs" / "b");
  for (const char* rel : {"report", "report/viewer", "jobs/b"}) {
    try {
      core::make_own_folder((dir / "run").string(), rel, "report: ");
      FAIL() << "made " << rel << " through a symlink";
    } catch (const JobError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(" is a symlink where shadowbench makes a folder of its own"),
                std::string::npos)
          << what;
    }
  }
  EXPECT_TRUE(outside.names().empty());
}

}  // namespace
}  // namespace sb
