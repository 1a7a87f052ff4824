#pragma once
// One server per database. SQLite itself would let two servers share the file, but lease
// expiry, claim wake-ups and WatchJob notifications live in the server's memory and assume
// they see every write; a second server (say, systemd's and a manual one) would leave its
// watchers waiting. The lock is an flock on "<db>.lock", released when the process exits.
#include <string>

namespace sph::server::store {

class DatabaseLock {
 public:
  // Throws std::runtime_error when another process holds the lock.
  explicit DatabaseLock(const std::string& db_path);
  ~DatabaseLock();
  DatabaseLock(const DatabaseLock&) = delete;
  DatabaseLock& operator=(const DatabaseLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace sph::server::store
