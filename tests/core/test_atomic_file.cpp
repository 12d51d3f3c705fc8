// core/atomic_file: a file appears whole under its name or not at all, and
// nothing is left behind that results/store.cpp would not recognise.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"

namespace sb {

using core::AtomicFile;
using core::is_atomic_temp_name;
using core::JobError;
using core::write_file_atomically;

namespace {

namespace fs = std::filesystem;

// A fresh folder of its own under the system's temporary folder.
class Folder {
 public:
  Folder() {
    std::string name = (fs::temp_directory_path() / "sb_atomic_file_XXXXXX").string();
    if (::mkdtemp(name.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = name;
  }
  ~Folder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  Folder(const Folder&) = delete;
  Folder& operator=(const Folder&) = delete;
  fs::path operator/(const std::string& name) const { return path_ / name; }
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(path_)) out.push_back(e.path().filename());
    return out;
  }

 private:
  fs::path path_;
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
  const AtomicFile a("/x/job.json"), b("/x/job.json");
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

}  // namespace
}  // namespace sb
