// Removing a finished job's files (sphctl delete): what is counted and what is left alone.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "server/results/job_files_removal.h"

namespace sph::server {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& p, std::size_t bytes) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << std::string(bytes, 'x');
}

TEST(JobFilesRemoval, RemovesEveryAttemptAndCountsOnlyItsOwnFiles) {
  std::string tmpl = (fs::temp_directory_path() / "sphd-removal-XXXXXX").string();
  ASSERT_NE(mkdtemp(tmpl.data()), nullptr);
  const fs::path root = tmpl;
  const ResultLayout layout(root / "results");
  const fs::path job = layout.job_dir("job-7");
  write(job / "1" / "result.h5", 1000);
  write(job / "1" / "checkpoints" / "ckpt_000100.h5", 300);
  write(job / "2" / "result.h5", 1500);
  write(job / "2" / "result.xmf", 20);
  // Links inside the job's folder are removed, not followed: the files they point to are
  // neither counted nor deleted.
  write(root / "elsewhere" / "precious.h5", 5000);
  fs::create_directory_symlink(root / "elsewhere", job / "2" / "linked_dir");
  fs::create_symlink(root / "elsewhere" / "precious.h5", job / "2" / "linked_file.h5");
  write(layout.job_dir("job-70") / "1" / "result.h5", 10);  // a neighbour with a similar name

  const JobFiles measured = measure_job_files(layout, "job-7");
  EXPECT_EQ(measured.files, 4);
  EXPECT_EQ(measured.bytes, 1000 + 300 + 1500 + 20);
  remove_job_files(layout, "job-7");
  EXPECT_FALSE(fs::exists(fs::symlink_status(job)));
  EXPECT_EQ(fs::file_size(root / "elsewhere" / "precious.h5"), 5000u);
  EXPECT_TRUE(fs::exists(layout.job_dir("job-70") / "1" / "result.h5"));

  const JobFiles again = measure_job_files(layout, "job-7");
  EXPECT_EQ(again.files, 0);
  EXPECT_EQ(again.bytes, 0);
  remove_job_files(layout, "job-7");  // nothing left to remove is no error
  fs::remove_all(root);
}

}  // namespace
}  // namespace sph::server
