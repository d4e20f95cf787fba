// Expected failures (bad scene files, missing maps, no Vulkan device): the third error tier.
//
// A function that can fail for reasons outside the programmer's control returns
// Result<T>: either a value or an Error whose message is ready to print as-is. Messages
// that refer to a file name it and, where there is one, the line and column
// ("scene.json:12:7: ..."). Results never throw; reading value() of an error is a
// programmer error and asserts.
#pragma once

#include "lantern/core/assert.hpp"

#include <string>
#include <utility>
#include <variant>

namespace lantern {

struct Error {
    std::string message;
    // Process exit status a command-line tool should use for this error (2 = bad input).
    int exit_code = 2;
};

template <typename T>
class [[nodiscard]] Result {
  public:
    Result(T value) : data_(std::in_place_index<0>, std::move(value)) {}
    Result(Error error) : data_(std::in_place_index<1>, std::move(error)) {}

    bool ok() const { return data_.index() == 0; }
    explicit operator bool() const { return ok(); }

    T& value() & {
        LANTERN_ASSERT(ok(), "value() of a failed Result");
        return std::get<0>(data_);
    }
    const T& value() const& {
        LANTERN_ASSERT(ok(), "value() of a failed Result");
        return std::get<0>(data_);
    }
    T&& value() && {
        LANTERN_ASSERT(ok(), "value() of a failed Result");
        return std::get<0>(std::move(data_));
    }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }

    const Error& error() const {
        LANTERN_ASSERT(!ok(), "error() of a successful Result");
        return std::get<1>(data_);
    }

  private:
    std::variant<T, Error> data_;
};

// Result<void>: success or an Error.
template <>
class [[nodiscard]] Result<void> {
  public:
    Result() = default;
    Result(Error error) : error_(std::move(error)), failed_(true) {}

    bool ok() const { return !failed_; }
    explicit operator bool() const { return ok(); }
    const Error& error() const {
        LANTERN_ASSERT(failed_, "error() of a successful Result");
        return error_;
    }

  private:
    Error error_;
    bool failed_ = false;
};

inline Error make_error(std::string message, int exit_code = 2) {
    return Error{std::move(message), exit_code};
}

} // namespace lantern
