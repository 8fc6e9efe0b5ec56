// The current call's stop token (cancel.hpp): one per thread, set by StopScope.
#include "nimbus/base/cancel.hpp"

#include <utility>

namespace nimbus {
namespace {
thread_local std::stop_token t_current;
}  // namespace

std::stop_token current_stop_token() { return t_current; }

StopScope::StopScope(std::stop_token token) : previous_(std::exchange(t_current, std::move(token))) {}
StopScope::~StopScope() { t_current = std::move(previous_); }

}  // namespace nimbus
