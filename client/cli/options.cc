#include "cli/options.h"

#include <cstdio>
#include <cstdlib>

namespace sph::ctl {

std::optional<GlobalOptions> take_global_options(std::vector<std::string>& args) {
  GlobalOptions g;
  if (const char* env = std::getenv("SPHCTL_SERVER"); env != nullptr && *env != '\0')
    g.server = env;
  if (const char* env = std::getenv("SPHCTL_TOKEN_FILE"); env != nullptr && *env != '\0')
    g.token_file = env;
  std::vector<std::string> rest;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&](std::string& out) {
      if (i + 1 >= args.size()) {
        std::fprintf(stderr, "sphctl: %s needs a value\n", a.c_str());
        return false;
      }
      out = args[++i];
      return true;
    };
    if (a == "--server") {
      if (!value(g.server)) return std::nullopt;
    } else if (a == "--token-file") {
      if (!value(g.token_file)) return std::nullopt;
    } else if (a == "--json") {
      g.json = true;
    } else if (a == "--timeout") {
      std::string v;
      if (!value(v)) return std::nullopt;
      char* end = nullptr;
      g.timeout_seconds = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end != '\0' || g.timeout_seconds <= 0) {
        std::fprintf(stderr, "sphctl: --timeout needs a positive number of seconds\n");
        return std::nullopt;
      }
    } else {
      rest.push_back(a);
    }
  }
  args = std::move(rest);
  return g;
}

bool ArgScanner::take_value(const std::string& name, std::string& value,
                            const std::string& short_name) {
  for (size_t i = 0; i < args_.size(); ++i) {
    if (args_[i] != name && (short_name.empty() || args_[i] != short_name)) continue;
    if (i + 1 >= args_.size()) {
      error_ = name + " needs a value";
      args_.erase(args_.begin() + static_cast<std::ptrdiff_t>(i));
      return false;
    }
    value = args_[i + 1];
    args_.erase(args_.begin() + static_cast<std::ptrdiff_t>(i),
                args_.begin() + static_cast<std::ptrdiff_t>(i + 2));
    return true;
  }
  return false;
}

bool ArgScanner::take_flag(const std::string& name) {
  for (size_t i = 0; i < args_.size(); ++i) {
    if (args_[i] == name) {
      args_.erase(args_.begin() + static_cast<std::ptrdiff_t>(i));
      return true;
    }
  }
  return false;
}

bool ArgScanner::positionals(std::vector<std::string>& out, std::string& error) const {
  if (!error_.empty()) {
    error = error_;
    return false;
  }
  for (const auto& a : args_) {
    if (a.size() > 1 && a[0] == '-') {
      error = "unknown option " + a;
      return false;
    }
    out.push_back(a);
  }
  return true;
}

}  // namespace sph::ctl
