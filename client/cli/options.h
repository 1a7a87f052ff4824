#pragma once
// Options every sphctl command understands, and a small argument scanner for the rest.
#include <optional>
#include <string>
#include <vector>

namespace sph::ctl {

struct GlobalOptions {
  std::string server = "127.0.0.1:7070";  // --server, else $SPHCTL_SERVER
  std::string token_file;                 // --token-file, else $SPHCTL_TOKEN_FILE
  bool json = false;                      // --json: machine-readable output on stdout
  double timeout_seconds = 30;            // --timeout: per unary call
};

// Removes the global options (wherever they appear) from args and returns them. On a bad
// value prints the problem and returns nullopt.
std::optional<GlobalOptions> take_global_options(std::vector<std::string>& args);

// The command's own arguments: flags with values, boolean flags and positionals.
class ArgScanner {
 public:
  explicit ArgScanner(std::vector<std::string> args) : args_(std::move(args)) {}
  // Removes "--name VALUE" (or "-n VALUE" when short is given); true when present.
  bool take_value(const std::string& name, std::string& value, const std::string& short_name = "");
  bool take_flag(const std::string& name);
  // What is left, once all flags were taken; fails on anything that looks like a flag.
  bool positionals(std::vector<std::string>& out, std::string& error) const;
  const std::string& error() const { return error_; }

 private:
  std::vector<std::string> args_;
  std::string error_;
};

}  // namespace sph::ctl
