#include <gtest/gtest.h>

#include "core/hash.h"

namespace {

TEST(referenceHash, Fnv1a64KnownVectors) {
  EXPECT_EQ(sb::core::fnv1a64(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(sb::core::fnv1a64("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(sb::core::fnv1a64("foobar"), 0x85944171f73967e8ull);
  EXPECT_EQ(sb::core::to_hex(0x85944171f73967e8ull), "85944171f73967e8");
}

TEST(referenceHash, HasherIsIncrementalAndTyped) {
  sb::core::Hasher a;
  a.add("foo", 3).add("bar", 3);
  EXPECT_EQ(a.value(), sb::core::fnv1a64("foobar"));
  EXPECT_EQ(a.hex().size(), 16u);
  // Strings carry their length: the split point matters.
  EXPECT_NE(sb::core::Hasher().add(std::string("ab")).add("c").value(),
            sb::core::Hasher().add("a").add(std::string("bc")).value());
  // Numbers hash their bytes, so the type matters too.
  EXPECT_NE(sb::core::Hasher().add(1).value(), sb::core::Hasher().add(1.0).value());
  EXPECT_NE(sb::core::Hasher().add(0.0f).value(), sb::core::Hasher().add(-0.0f).value());
  EXPECT_EQ(sb::core::Hasher().add(uint64_t(7)).value(),
            sb::core::Hasher().add(uint64_t(7)).value());
}

}  // namespace
