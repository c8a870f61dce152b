// Sets (or, with nullptr, removes) an environment variable for one scope, on Linux and Windows.
#pragma once

#include <cstdlib>
#include <optional>
#include <string>
#include <utility>

namespace mocaplink::testing_support {

class ScopedEnv {
 public:
  ScopedEnv(std::string name, const char* value) : name_(std::move(name)) {
    if (const char* old = std::getenv(name_.c_str())) old_ = old;
    set(value);
  }
  ~ScopedEnv() { set(old_ ? old_->c_str() : nullptr); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  void set(const char* value) {
#ifdef _WIN32
    ::_putenv_s(name_.c_str(), value != nullptr ? value : "");  // "" removes it on Windows
#else
    if (value != nullptr) {
      ::setenv(name_.c_str(), value, 1);
    } else {
      ::unsetenv(name_.c_str());
    }
#endif
  }
  std::string name_;
  std::optional<std::string> old_;
};

}  // namespace mocaplink::testing_support
