// File names made from user labels: readable where that is one-to-one,
// hashed otherwise, and never a path out of the run folder or a hidden file.
#include <gtest/gtest.h>

#include <cctype>
#include <set>
#include <string>
#include <vector>

#include "core/names.h"

namespace sb {

using core::file_safe;
using core::job_id;

namespace {

void expect_safe(const std::string& name) {
  const std::string f = file_safe(name);
  SCOPED_TRACE("name \"" + name + "\" -> \"" + f + "\"");
  EXPECT_FALSE(f.empty());
  EXPECT_LE(f.size(), 77u);
  EXPECT_NE(f[0], '.');
  for (char c : f)
    EXPECT_TRUE(std::isalnum(static_cast<unsigned char>(c)) ||
                std::string("._=+-~").find(c) != std::string::npos)
        << int(c);
}

TEST(Names, OrdinaryVariantNamesStayReadable) {
  EXPECT_EQ(file_safe("pcf_box/k=3,size=1024"), "pcf_box--k=3+size=1024");
  EXPECT_EQ(file_safe("sphere_grid"), "sphere_grid");
  EXPECT_EQ(job_id("sphere_grid/grid=2", "64x48", "none"), "sphere_grid--grid=2__64x48__none");
}

TEST(Names, DistinctLabelsNeverShareAFile) {
  // Each group used to map to one name.
  const std::vector<std::vector<std::string>> groups = {
      {"α", "β", "--", "-"},
      {"x y", "x-y", "x+y"},
      {"a/b", "a--b"},
      {"a-/b", "a/-b", "a---b"},
      {"x__y", "x_y"},
      {std::string("a\0b", 3), "a"},
      {std::string(300, 'L'), std::string(301, 'L'), std::string(64, 'L') + "M"}};
  std::set<std::string> all;
  size_t count = 0;
  for (const auto& g : groups)
    for (const auto& name : g) {
      expect_safe(name);
      all.insert(file_safe(name));
      ++count;
    }
  EXPECT_EQ(all.size(), count);
}

TEST(Names, NoHiddenFilesOrParentFolders) {
  for (const std::string name : {"..", "../../etc/passwd", ".hidden", "...", "/abs", "a\\b"})
    expect_safe(name);
  EXPECT_EQ(file_safe("../x").find(".."), std::string::npos);
  EXPECT_EQ(file_safe("a/../b").find('/'), std::string::npos);
}

TEST(Names, NonUtf8BytesBecomeAsciiNames) {
  expect_safe(std::string("\xff\xfe label", 8));
  EXPECT_NE(file_safe("\xff"), file_safe("\xfe"));
}

}  // namespace
}  // namespace sb
