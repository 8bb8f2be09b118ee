#include "core/sha256.h"

#include <gtest/gtest.h>

#include "core/test_files.h"

namespace markerbench {
namespace {

// FIPS 180-4 examples (and the empty message), as printed by sha256sum.
TEST(Sha256, MatchesTheStandardExamples) {
  EXPECT_EQ(Sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(Sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(Sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256, IncrementalUpdatesEqualOneUpdate) {
  const std::string text(1000, 'x');
  Sha256 sha;
  sha.Update(text.substr(0, 63));
  sha.Update(text.substr(63, 2));
  sha.Update(text.substr(65));
  EXPECT_EQ(sha.HexDigest(), Sha256Hex(text));
}

TEST(Sha256, HashesFiles) {
  EXPECT_EQ(Sha256OfFile(WriteTestFile("sha.txt", "abc")), Sha256Hex("abc"));
  EXPECT_THROW(Sha256OfFile("/nonexistent/file"), std::runtime_error);
}

}  // namespace
}  // namespace markerbench
