// Environment variables for the backends a test makes: the CUDA tuning knobs
// (sim/cuda/tuning.h), which a backend reads when it is made.
#pragma once

#include <QByteArray>
#include <QScopeGuard>
#include <QtGlobal>

#include <initializer_list>
#include <utility>
#include <vector>

/// Sets each variable (an empty value leaves it unset); the returned guard unsets them.
inline auto scoped_env(std::initializer_list<std::pair<const char*, QByteArray>> vars) {
  std::vector<QByteArray> names;
  for (const auto& [name, value] : vars)
    if (!value.isEmpty()) {
      qputenv(name, value);
      names.emplace_back(name);
    }
  return qScopeGuard([names] {
    for (const auto& n : names) qunsetenv(n.constData());
  });
}
