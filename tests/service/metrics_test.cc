// sph-server --metrics-address: the Prometheus text at /metrics, scraped during real runs on a
// real one-rank pool (and a fake pool that claims a job and goes silent, for a lost lease).
#include <gtest/gtest.h>
#include <httplib.h>

#include <unistd.h>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "harness/service_harness.h"

namespace sph::testing {
namespace {

namespace fs = std::filesystem;

std::string channel(double end_time) {
  return with_end_time(read_test_case("channel_2d.textproto"), end_time);
}

struct Scrape {
  int status = 0;
  std::string content_type, body;
  // The value of the sample `key` (name and labels exactly as written), NaN when absent.
  double value(const std::string& key) const {
    const std::string prefix = "\n" + key + " ";
    const auto at = ("\n" + body).find(prefix);
    if (at == std::string::npos) return std::nan("");
    return std::stod(body.substr(at + prefix.size() - 1));
  }
};

Scrape scrape(const std::string& address) {
  const auto colon = address.rfind(':');
  httplib::Client http(address.substr(0, colon), std::stoi(address.substr(colon + 1)));
  auto res = http.Get("/metrics");
  Scrape s;
  if (!res) return s;
  s.status = res->status;
  s.content_type = res->get_header_value("Content-Type");
  s.body = res->body;
  return s;
}

std::string pool_host() {
  char name[256] = {};
  gethostname(name, sizeof name - 1);
  return name;
}

std::string metrics_address(ServiceHarness& h) {
  std::ifstream in(h.dir() + "/metrics.address");
  std::string a;
  std::getline(in, a);
  return a;
}

TEST(ServiceMetrics, ScrapedDuringARun) {
  ServiceHarness h;
  h.start_server(ServerSettings()
                     .lease(1.5)
                     .flag("--metrics-address", "127.0.0.1:0")
                     .flag("--metrics-address-file", h.dir() + "/metrics.address"));
  const std::string m = metrics_address(h);
  ASSERT_FALSE(m.empty()) << h.logs();

  // Before anything: every state at 0, no pools.
  Scrape s = scrape(m);
  ASSERT_EQ(s.status, 200) << h.logs();
  EXPECT_NE(s.content_type.find("text/plain; version=0.0.4"), std::string::npos) << s.content_type;
  EXPECT_EQ(s.value("sphd_jobs{state=\"QUEUED\"}"), 0) << s.body;
  EXPECT_EQ(s.value("sphd_pools_seen"), 0) << s.body;

  // A fake pool claims a job and goes silent: its lease expires and the job is queued again.
  const auto lost = h.submit_text(channel(5));
  ASSERT_EQ(h.claim("silent-pool", 3).job_id(), lost.id());
  ASSERT_TRUE(h.wait_for_job(lost.id(), 20s, [](const v1::Job& j) {
    return j.state() == v1::JOB_STATE_QUEUED && j.attempt() == 1;
  })) << h.logs();

  // A real pool takes it over; a second job waits in the queue meanwhile.
  auto pool = h.start_pool(1, {"--max-jobs", "2", "--idle-exit", "60"});
  ASSERT_TRUE(h.wait_for_job(lost.id(), 60s, [](const v1::Job& j) {
    return j.state() == v1::JOB_STATE_RUNNING && j.has_progress() && j.progress().step() > 0;
  })) << h.logs();
  const auto queued = h.submit_text(channel(0.1));
  s = scrape(m);
  std::printf("during the run:\n%s\n", s.body.c_str());
  EXPECT_EQ(s.value("sphd_jobs{state=\"RUNNING\"}"), 1);
  EXPECT_EQ(s.value("sphd_queue_depth"), 1);
  EXPECT_GT(s.value("sphd_queued_particles"), 100);
  EXPECT_EQ(s.value("sphd_attempts_started_total"), 2);
  EXPECT_EQ(s.value("sphd_attempts_running"), 1);
  EXPECT_EQ(s.value("sphd_lease_expiries_total"), 1);
  EXPECT_EQ(s.value("sphd_attempts_finished_total{outcome=\"LEASE_EXPIRED\"}"), 1);
  EXPECT_EQ(s.value("sphd_attempts_requeued_total"), 1);
  EXPECT_EQ(s.value("sphd_pools_seen"), 2);
  EXPECT_EQ(s.value("sphd_pool_ranks{pool=\"silent-pool\",host=\"\"}"), 3);
  EXPECT_EQ(s.value("sphd_submits_total{code=\"OK\"}"), 2);
  EXPECT_GE(s.value("sphd_rpc_duration_seconds_count{service=\"sph.v1.WorkerService\","
                    "method=\"Report\",code=\"OK\"}"),
            1);
  // Cumulative buckets end at the count.
  const std::string submit = "service=\"sph.v1.JobService\",method=\"Submit\",code=\"OK\"";
  EXPECT_EQ(s.value("sphd_rpc_duration_seconds_bucket{" + submit + ",le=\"+Inf\"}"), 2);
  EXPECT_GT(s.value("sphd_rpc_duration_seconds_sum{" + submit + "}"), 0);
  // The real pool by its "host:pid" id and its host name.
  EXPECT_NE(s.body.find("sphd_pool_ranks{pool=\"" + pool_host() + ":"), std::string::npos)
      << s.body;

  ASSERT_TRUE(h.wait_for_state(lost.id(), v1::JOB_STATE_SUCCEEDED, 120s)) << h.logs();
  ASSERT_TRUE(h.wait_for_state(queued.id(), v1::JOB_STATE_SUCCEEDED, 60s)) << h.logs();
  // A refused submit counts under its code.
  v1::SubmitRequest bad;
  bad.set_request_id("bad-case");
  bad.set_case_text("dimension: 7");
  v1::SubmitResponse resp;
  EXPECT_EQ(h.jobs().Submit(h.context().get(), bad, &resp).error_code(),
            grpc::StatusCode::INVALID_ARGUMENT);

  s = scrape(m);
  std::printf("after the runs:\n%s\n", s.body.c_str());
  EXPECT_EQ(s.value("sphd_jobs{state=\"SUCCEEDED\"}"), 2);
  EXPECT_EQ(s.value("sphd_queue_depth"), 0);
  EXPECT_EQ(s.value("sphd_attempts_running"), 0);
  EXPECT_EQ(s.value("sphd_attempts_finished_total{outcome=\"COMPLETED\"}"), 2);
  EXPECT_EQ(s.value("sphd_submits_total{code=\"INVALID_ARGUMENT\"}"), 1);
  double manifest_bytes = 0;
  for (const auto& id : {lost.id(), queued.id()}) {
    const v1::Job job = h.get_job(id);
    for (const auto& f : job.result().files()) manifest_bytes += static_cast<double>(f.size());
  }
  EXPECT_EQ(s.value("sphd_result_bytes"), manifest_bytes);
  EXPECT_GT(manifest_bytes, 0);
  EXPECT_EQ(pool.wait(30s).value_or(-1), 0) << h.logs();
}

TEST(ServiceMetrics, RefusesABadAddress) {
  ServiceHarness h;
  EXPECT_THROW(h.start_server(ServerSettings().flag("--metrics-address", "127.0.0.1:99999")),
               std::runtime_error);
  EXPECT_NE(h.logs().find("--metrics-address: the port must be 0..65535"), std::string::npos)
      << h.logs();
}

}  // namespace
}  // namespace sph::testing
