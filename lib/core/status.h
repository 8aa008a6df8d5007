// Status / StatusOr: the error type of every eqmesh API (no exceptions cross it).
// Modelled on Draco's core/status.h: a small code plus a human message that names
// the file, primitive or stream offset the problem came from.
#pragma once

#include <cassert>
#include <optional>
#include <string>
#include <utility>

namespace eqmesh {

enum class StatusCode {
  kOk = 0,
  kIoError,              // file missing, unreadable, unwritable
  kParseError,           // malformed text or binary input file
  kInvalidArgument,      // caller passed something out of range
  kInvalidMesh,          // mesh violates a precondition (non-manifold, NaN, ...)
  kCorruptStream,        // bitstream malformed, truncated or hostile
  kUnsupportedVersion,   // bitstream version this build cannot read
  kUnsupportedFeature,   // valid input using something not implemented
  kResourceLimit,        // a declared count exceeds what we agree to allocate
  kInternal,             // a bug: an invariant of our own code failed
  kTargetOutOfReach,     // a quality target the input cannot meet (says the best reached)
  kOutbid,               // a candidate stream given up: it cannot beat the one it competes with
};

const char* StatusCodeName(StatusCode code);

class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(StatusCode code, std::string message) : code_(code), message_(std::move(message)) {}

  static Status Ok() { return Status(); }
  bool ok() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }
  std::string ToString() const;

  // Prefixes the message with context ("bunny.ply: " + message) keeping the code.
  Status WithContext(const std::string& context) const {
    if (ok()) return *this;
    return Status(code_, context + ": " + message_);
  }

 private:
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

inline Status IoError(std::string m) { return Status(StatusCode::kIoError, std::move(m)); }
inline Status ParseError(std::string m) { return Status(StatusCode::kParseError, std::move(m)); }
inline Status InvalidArgument(std::string m) { return Status(StatusCode::kInvalidArgument, std::move(m)); }
inline Status InvalidMesh(std::string m) { return Status(StatusCode::kInvalidMesh, std::move(m)); }
inline Status CorruptStream(std::string m) { return Status(StatusCode::kCorruptStream, std::move(m)); }
inline Status UnsupportedVersion(std::string m) { return Status(StatusCode::kUnsupportedVersion, std::move(m)); }
inline Status UnsupportedFeature(std::string m) { return Status(StatusCode::kUnsupportedFeature, std::move(m)); }
inline Status ResourceLimit(std::string m) { return Status(StatusCode::kResourceLimit, std::move(m)); }
inline Status InternalError(std::string m) { return Status(StatusCode::kInternal, std::move(m)); }

template <typename T>
class [[nodiscard]] StatusOr {
 public:
  StatusOr(const Status& status) : status_(status) {  // NOLINT: implicit by design
    assert(!status_.ok() && "StatusOr built from an OK status without a value");
    if (status_.ok()) status_ = InternalError("StatusOr constructed from OK status without a value");
  }
  StatusOr(T value) : value_(std::move(value)) {}  // NOLINT: implicit by design

  bool ok() const { return status_.ok(); }
  const Status& status() const { return status_; }
  const T& value() const& { assert(ok()); return *value_; }
  T& value() & { assert(ok()); return *value_; }
  T&& value() && { assert(ok()); return std::move(*value_); }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }

 private:
  Status status_;
  std::optional<T> value_;
};

inline const char* StatusCodeName(StatusCode code) {
  switch (code) {
    case StatusCode::kOk: return "OK";
    case StatusCode::kIoError: return "IO_ERROR";
    case StatusCode::kParseError: return "PARSE_ERROR";
    case StatusCode::kInvalidArgument: return "INVALID_ARGUMENT";
    case StatusCode::kInvalidMesh: return "INVALID_MESH";
    case StatusCode::kCorruptStream: return "CORRUPT_STREAM";
    case StatusCode::kUnsupportedVersion: return "UNSUPPORTED_VERSION";
    case StatusCode::kUnsupportedFeature: return "UNSUPPORTED_FEATURE";
    case StatusCode::kResourceLimit: return "RESOURCE_LIMIT";
    case StatusCode::kInternal: return "INTERNAL";
    case StatusCode::kTargetOutOfReach: return "TARGET_OUT_OF_REACH";
    case StatusCode::kOutbid: return "OUTBID";
  }
  return "UNKNOWN";
}

inline std::string Status::ToString() const {
  if (ok()) return "OK";
  return std::string(StatusCodeName(code_)) + ": " + message_;
}

}  // namespace eqmesh

#define EQMESH_CONCAT_INNER(a, b) a##b
#define EQMESH_CONCAT(a, b) EQMESH_CONCAT_INNER(a, b)

#define EQMESH_RETURN_IF_ERROR(expr)                 \
  do {                                               \
    ::eqmesh::Status eqmesh_status_ = (expr);        \
    if (!eqmesh_status_.ok()) return eqmesh_status_; \
  } while (0)

#define EQMESH_ASSIGN_OR_RETURN_IMPL(tmp, lhs, expr) \
  auto tmp = (expr);                                 \
  if (!tmp.ok()) return tmp.status();                \
  lhs = std::move(tmp).value()

#define EQMESH_ASSIGN_OR_RETURN(lhs, expr) \
  EQMESH_ASSIGN_OR_RETURN_IMPL(EQMESH_CONCAT(eqmesh_statusor_, __LINE__), lhs, expr)
