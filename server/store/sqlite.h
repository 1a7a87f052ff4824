#pragma once
// A thin RAII layer over the SQLite C API: a connection, prepared statements and write
// transactions. Only sph-server opens the database (DESIGN.md).
#include <sqlite3.h>

#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace sph::server::store {

class SqliteError : public std::runtime_error {
 public:
  SqliteError(int code, const std::string& what) : std::runtime_error(what), code_(code) {}
  int code() const { return code_; }

 private:
  int code_;
};

class Statement {
 public:
  // Prepares `sql`; finalized when destroyed.
  Statement(sqlite3* db, std::string_view sql);
  // Finalizes, or for a statement lent by Database::prepare's cache, resets it and clears its
  // bindings, so that it holds no read snapshot and can be lent again.
  ~Statement();
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  Statement(Statement&& other) noexcept;
  Statement& operator=(Statement&&) = delete;

  // Parameters are 1-based, as in SQLite.
  Statement& bind(int index, std::int64_t value);
  Statement& bind(int index, int value) { return bind(index, static_cast<std::int64_t>(value)); }
  Statement& bind(int index, double value);
  Statement& bind(int index, std::string_view text);
  Statement& bind(int index, const char* text) { return bind(index, std::string_view(text)); }
  Statement& bind(int index, const std::string& text) {
    return bind(index, std::string_view(text));
  }
  Statement& bind_blob(int index, std::string_view bytes);
  Statement& bind_null(int index);

  // Steps once: true while a row is available.
  bool step();
  // Steps to completion (for statements without result rows).
  void run();

  // Columns are 0-based, as in SQLite.
  bool is_null(int column) const;
  std::int64_t int64(int column) const;
  double real(int column) const;
  std::string text(int column) const;
  std::string blob(int column) const;

 private:
  friend class Database;
  Statement(sqlite3* db, sqlite3_stmt* cached, bool* lent);
  void check(int rc, const char* what) const;
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
  bool* lent_ = nullptr;  // the cache's flag, for a statement the cache owns
};

class Database {
 public:
  // Opens (creating if needed) with WAL, synchronous=FULL and foreign keys on.
  explicit Database(const std::string& path);
  ~Database();
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  void exec(std::string_view sql);
  // A statement for `sql`, prepared once per connection and lent out again on later calls
  // (preparing costs more than running most of the store's statements). A statement still
  // lent out when the same text is asked for again is prepared afresh for that caller.
  Statement prepare(std::string_view sql);
  std::int64_t changes() const { return sqlite3_changes64(db_); }
  sqlite3* handle() { return db_; }
  // How many statements the connection keeps prepared.
  std::size_t cached_statements() const { return cache_.size(); }

 private:
  struct Cached {
    sqlite3_stmt* stmt = nullptr;
    bool lent = false;
  };
  // Statements built from request contents (a list of states) vary; past this many distinct
  // texts the rest are prepared per call.
  static constexpr std::size_t kMaxCachedStatements = 64;
  sqlite3* db_ = nullptr;
  std::map<std::string, Cached, std::less<>> cache_;
};

// BEGIN IMMEDIATE ... COMMIT. Every transaction that writes takes the write lock up front: a
// deferred transaction that reads and then writes can fail with SQLITE_BUSY in WAL mode, and
// no busy timeout can fix that. Rolls back in the destructor unless committed.
class WriteTransaction {
 public:
  explicit WriteTransaction(Database& db);
  ~WriteTransaction();
  WriteTransaction(const WriteTransaction&) = delete;
  WriteTransaction& operator=(const WriteTransaction&) = delete;
  void commit();

 private:
  Database& db_;
  bool done_ = false;
};

}  // namespace sph::server::store
