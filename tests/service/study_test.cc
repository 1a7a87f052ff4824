// Convergence studies through the service: `sphctl study` submits a ladder, a two-rank pool
// runs it and publishes study.csv/md/png with every level's result, studies are validated at
// the door (a case without a reference, a bad ladder), and a study whose pool is lost resumes
// on another pool without running its finished levels again.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "harness/service_harness.h"

namespace sph::testing {
namespace {

namespace fs = std::filesystem;

std::string write_case(ServiceHarness& h, const std::string& name, const std::string& text) {
  const std::string path = h.dir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

// The data rows of a study.csv as column name -> value maps.
std::vector<std::map<std::string, std::string>> study_rows(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::map<std::string, std::string>> rows;
  std::vector<std::string> header;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    if (header.empty()) {
      header = cells;
      continue;
    }
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < cells.size(); ++i) row[header[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}

std::set<std::string> manifest_names(const v1::Job& j) {
  std::set<std::string> names;
  for (const auto& f : j.result().files()) names.insert(f.name());
  return names;
}

TEST(ServiceStudy, SphctlStudyRunsTheLadderOnAPoolAndFetchesTheReport) {
  ServiceHarness h;
  h.start_server();
  auto pool = h.start_pool(2, {"--max-jobs", "1", "--idle-exit", "60"});
  const auto r = h.sphctl(
      {"study", test_case_path("tiny_conduction_2d.textproto"), "--refine", "3", "--watch"}, 180s);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err << h.logs();
  EXPECT_NE(r.out.find("submitted job-1 (tiny_conduction_2d, convergence study"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("progress level "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("SUCCEEDED"), std::string::npos) << r.out;

  const v1::Job job = h.get_job("job-1");
  ASSERT_TRUE(job.has_study());
  EXPECT_EQ(job.study().refine(), 3);
  EXPECT_NE(job.reason().find("study of 3 levels: observed order"), std::string::npos)
      << job.reason();
  const auto names = manifest_names(job);
  for (const char* f : {"study.csv", "study.md", "study.png", "level_1/result.h5",
                        "level_2/result.h5", "level_3/result.h5", "level_3/result.xmf"})
    EXPECT_TRUE(names.count(f)) << f << " is not in the manifest";

  const auto status = h.sphctl({"status", "job-1"});
  EXPECT_EQ(status.exit_code, 0);
  EXPECT_NE(status.out.find("study:      3 levels"), std::string::npos) << status.out;
  EXPECT_NE(status.out.find("level_2/result.h5"), std::string::npos) << status.out;
  const auto json = h.sphctl({"status", "job-1", "--json"});
  EXPECT_NE(json.out.find("\"study\":{\"refine\":3"), std::string::npos) << json.out;

  const std::string out = h.dir() + "/fetched";
  const auto fetched = h.sphctl({"fetch", "job-1", "-o", out});
  ASSERT_EQ(fetched.exit_code, 0) << fetched.err;
  for (const char* f : {"study.csv", "study.md", "study.png", "level_1/result.h5"})
    EXPECT_TRUE(fs::is_regular_file(fs::path(out) / f)) << f;
  const auto rows = study_rows(out + "/study.csv");
  ASSERT_EQ(rows.size(), 3u) << "one row per level";
  for (std::size_t k = 0; k < rows.size(); ++k) {
    EXPECT_EQ(rows[k].at("level"), std::to_string(k + 1));
    EXPECT_EQ(rows[k].at("status"), "completed");
    EXPECT_EQ(rows[k].at("ranks"), "2");
    EXPECT_GT(std::stod(rows[k].at("error")), 0);
    if (k > 0) {
      EXPECT_LT(std::stod(rows[k].at("dx")), std::stod(rows[k - 1].at("dx")));
    }
  }
  std::ifstream md(out + "/study.md");
  std::stringstream text;
  text << md.rdbuf();
  EXPECT_NE(text.str().find("Observed order"), std::string::npos) << text.str();
  EXPECT_EQ(pool.wait(30s).value_or(-1), 0) << h.logs();
}

TEST(ServiceStudy, StudiesAreValidatedAtTheDoor) {
  ServiceHarness h;
  h.start_server();
  const std::string tiny = test_case_path("tiny_conduction_2d.textproto");
  // sphctl checks before it submits: no reference, no ladder, a bad ladder.
  const auto no_ref = h.sphctl({"study", test_case_path("channel_2d.textproto"), "--refine", "3"});
  EXPECT_EQ(no_ref.exit_code, 3);
  EXPECT_NE(no_ref.err.find("reference: a convergence study needs"), std::string::npos)
      << no_ref.err;
  EXPECT_EQ(h.sphctl({"study", tiny}).exit_code, 2);
  EXPECT_EQ(h.sphctl({"study", tiny, "--dx", "0.04,x"}).exit_code, 2);
  const auto one = h.sphctl({"study", tiny, "--refine", "1"});
  EXPECT_EQ(one.exit_code, 3);
  EXPECT_NE(one.err.find("study.refine"), std::string::npos) << one.err;
  const auto dry = h.sphctl({"study", tiny, "--dx", "0.04,0.02", "--dry-run"});
  EXPECT_EQ(dry.exit_code, 0) << dry.err;
  EXPECT_NE(dry.out.find("study of tiny_conduction_2d"), std::string::npos) << dry.out;
  EXPECT_NE(dry.out.find("0.02"), std::string::npos) << dry.out;

  // The server checks the same through the API, names the field, and stores nothing.
  auto submit = [&](const std::string& text, const v1::StudySpec& spec, std::string& field) {
    static int n = 0;
    v1::SubmitRequest req;
    req.set_request_id("study-" + std::to_string(++n));
    req.set_case_text(text);
    *req.mutable_study() = spec;
    v1::SubmitResponse resp;
    auto ctx = h.context();
    const grpc::Status s = h.jobs().Submit(ctx.get(), req, &resp);
    field.clear();
    const auto& md = ctx->GetServerTrailingMetadata();
    if (auto it = md.find("sph-invalid-field"); it != md.end())
      field.assign(it->second.data(), it->second.size());
    return s;
  };
  v1::StudySpec three;
  three.set_refine(3);
  std::string field;
  grpc::Status s = submit(read_test_case("channel_2d.textproto"), three, field);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(s.error_message().find("invalid study: reference:"), std::string::npos)
      << s.error_message();
  EXPECT_EQ(field, "reference");
  const std::string tiny_text = read_test_case("tiny_conduction_2d.textproto");
  v1::StudySpec bad_ratio = three;
  bad_ratio.set_ratio(0.5);
  s = submit(tiny_text, bad_ratio, field);
  EXPECT_EQ(s.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(field, "study.ratio") << s.error_message();
  v1::StudySpec bad_dx;
  bad_dx.add_dx(0.04);
  bad_dx.add_dx(-1);
  s = submit(tiny_text, bad_dx, field);
  EXPECT_EQ(field, "study.dx[1]") << s.error_message();
  v1::StudySpec empty;
  s = submit(tiny_text, empty, field);
  EXPECT_EQ(field, "study.refine") << s.error_message();
  EXPECT_NE(h.sphctl({"list", "--json"}).out.find("\"jobs\":[]"), std::string::npos)
      << "a rejected study was stored";

  // A request id names one submission: the same case as a study is a different one.
  EXPECT_EQ(h.sphctl({"study", tiny, "--refine", "2", "--request-id", "same"}).exit_code, 0);
  const auto plain = h.sphctl({"submit", tiny, "--request-id", "same"});
  EXPECT_EQ(plain.exit_code, 8) << plain.out << plain.err;
}

TEST(ServiceStudy, ACancelledStudyStopsAndKeepsTheReportOfItsFinishedLevels) {
  ServiceHarness h;
  h.start_server();
  auto pool = h.start_pool(2, {"--max-jobs", "1"});
  // Level 3 (dx = 0.01, 10 000 steps) runs long enough for the cancel to find it running
  // (at t = 0.03 it once finished first on two loaded cores: the slab at rest never searches
  // its neighbours again).
  const std::string path = write_case(
      h, "slab.textproto", with_end_time(read_test_case("tiny_conduction_2d.textproto"), 0.1));
  ASSERT_EQ(h.sphctl({"study", path, "--dx", "0.04,0.02,0.01"}).exit_code, 0);
  ASSERT_TRUE(h.wait_for_job("job-1", 120s, [](const v1::Job& j) {
    return j.has_progress() && j.progress().study().level() == 3 && j.progress().step() > 0;
  })) << h.logs();
  ASSERT_EQ(h.sphctl({"cancel", "job-1"}).exit_code, 0);
  ASSERT_TRUE(h.wait_for_state("job-1", v1::JOB_STATE_CANCELLED, 30s)) << h.logs();
  const v1::Job done = h.get_job("job-1");
  const auto names = manifest_names(done);
  EXPECT_TRUE(names.count("study.csv") && names.count("study.md") &&
              names.count("level_3/result.h5"))
      << "the partial study is not in the manifest";
  const auto rows = study_rows(done.result().output_dir() + "/study.csv");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].at("status"), "completed");
  EXPECT_EQ(rows[1].at("status"), "completed");
  EXPECT_EQ(rows[2].at("status"), "cancelled");
  EXPECT_EQ(h.sphctl({"watch", "job-1"}).exit_code, 11);
  EXPECT_EQ(pool.wait(30s).value_or(-1), 0) << h.logs();
}

TEST(ServiceStudy, ALostPoolsStudyReusesItsFinishedLevelsOnTheNextPool) {
  ServiceHarness h;
  h.start_server(ServerSettings().lease(2));
  // Level 3 (dx = 0.01, 3000 steps) runs long enough to be killed with a checkpoint.
  const std::string path = write_case(
      h, "slab.textproto", with_end_time(read_test_case("tiny_conduction_2d.textproto"), 0.03));
  const auto submitted = h.sphctl({"study", path, "--dx", "0.04,0.02,0.01"});
  ASSERT_EQ(submitted.exit_code, 0) << submitted.err;
  auto first = h.start_pool(2, {"--checkpoint-interval", "0.25"}, "pool1");
  ASSERT_TRUE(h.wait_for_job("job-1", 120s, [](const v1::Job& j) {
    return j.has_progress() && j.progress().study().level() == 3 && j.has_checkpoint() &&
           j.checkpoint().path().find("/level_3/checkpoints/") != std::string::npos;
  })) << h.logs();
  first.kill_all();  // kill -9 in the middle of level 3
  ASSERT_NE(h.get_job("job-1").state(), v1::JOB_STATE_SUCCEEDED) << "the study ended too soon";
  ASSERT_TRUE(h.wait_for_state("job-1", v1::JOB_STATE_QUEUED, 15s)) << h.logs();

  auto second = h.start_pool(2, {"--max-jobs", "1"}, "pool2");
  ASSERT_TRUE(h.wait_for_state("job-1", v1::JOB_STATE_SUCCEEDED, 180s)) << h.logs();
  const v1::Job done = h.get_job("job-1");
  ASSERT_EQ(done.attempts_size(), 2);
  EXPECT_EQ(done.attempts(0).outcome(), v1::ATTEMPT_LEASE_EXPIRED);
  EXPECT_EQ(done.result().attempt(), 2);
  const auto rows = study_rows(done.result().output_dir() + "/study.csv");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].at("reused"), "1") << "level 1 ran again";
  EXPECT_EQ(rows[1].at("reused"), "1") << "level 2 ran again";
  EXPECT_EQ(rows[2].at("reused"), "0");
  EXPECT_EQ(rows[2].at("resumed"), "1") << "level 3 started over instead of resuming";
  for (const auto& row : rows) EXPECT_EQ(row.at("status"), "completed");
  // The reused levels' files are in this attempt's directory (the manifest names no other).
  EXPECT_TRUE(fs::is_regular_file(done.result().output_dir() + "/level_1/result.h5"));
  EXPECT_EQ(second.wait(30s).value_or(-1), 0) << h.logs();
}

}  // namespace
}  // namespace sph::testing
