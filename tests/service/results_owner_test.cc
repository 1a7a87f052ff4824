// A results directory belongs to one database (server/results/results_owner.h).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "server/results/results_owner.h"

namespace sph::server {
namespace {

namespace fs = std::filesystem;

class ResultsOwner : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string tmpl = (fs::temp_directory_path() / "sphd-owner-XXXXXX").string();
    ASSERT_NE(mkdtemp(tmpl.data()), nullptr);
    root_ = tmpl;
  }
  void TearDown() override { fs::remove_all(root_); }
  std::string marker() const {
    std::ifstream in(root_ / kDatabaseIdFile);
    std::string s;
    std::getline(in, s);
    return s;
  }
  // The message of the refusal, or "" when the directory was accepted.
  std::string refusal(const std::string& id, bool has_jobs) {
    try {
      claim_results_directory(ResultLayout(root_), id, has_jobs);
      return "";
    } catch (const std::runtime_error& e) {
      return e.what();
    }
  }
  fs::path root_;
};

TEST_F(ResultsOwner, AnEmptyDirectoryTakesTheDatabasesIdentityAndKeepsIt) {
  EXPECT_EQ(refusal("aaaa", false), "");
  EXPECT_EQ(marker(), "aaaa");
  fs::create_directories(root_ / "job-1" / "1");
  EXPECT_EQ(refusal("aaaa", true), "");  // the same database again
  EXPECT_EQ(marker(), "aaaa");
}

TEST_F(ResultsOwner, AnotherDatabaseIsRefusedNamingBoth) {
  ASSERT_EQ(refusal("aaaa", false), "");
  const std::string why = refusal("bbbb", false);
  EXPECT_NE(why.find("belongs to another database"), std::string::npos) << why;
  EXPECT_NE(why.find("aaaa"), std::string::npos) << why;
  EXPECT_NE(why.find("bbbb"), std::string::npos) << why;
  EXPECT_NE(refusal("bbbb", true), "");  // with jobs of its own too
  EXPECT_EQ(marker(), "aaaa");
}

TEST_F(ResultsOwner, JobFoldersWithoutAnIdentityAreNotGivenToANewDatabase) {
  fs::create_directories(root_ / "job-3" / "1");
  const std::string why = refusal("cccc", false);
  EXPECT_NE(why.find("holds job folders but this database is new"), std::string::npos) << why;
  EXPECT_FALSE(fs::exists(root_ / kDatabaseIdFile));
  // A database that has jobs wrote them before identities existed: it takes the directory.
  EXPECT_EQ(refusal("dddd", true), "");
  EXPECT_EQ(marker(), "dddd");
}

}  // namespace
}  // namespace sph::server
