#pragma once
// A technique's keys, each bound to the field of its settings struct that holds it: the one place
// where a key's name, field, type, range, doc and tunability are written. A key's default is its
// field's initial value in a value-initialised S, so the struct and the declaration cannot
// disagree. The technique's parameter list, a run's Settings read into S, and S written back into
// Settings all come from the table: a misspelt key cannot compile into a silent default.
#include <functional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "technique_api/parameters.h"
#include "technique_api/settings.h"

namespace aor {

inline constexpr bool kTunable = true;  // the `tunable` argument of floatKey and intKey

template <class S>
struct BoundKey {
  Parameter parameter;
  std::function<void(S&, double)> store;
  std::function<double(const S&)> load;
};

namespace key_table_detail {

template <class F>
F fromValue(double value) {
  if constexpr (std::is_enum_v<F>) return F(std::underlying_type_t<F>(value));
  else return static_cast<F>(value);
}

template <class F>
double toValue(F value) {
  if constexpr (std::is_enum_v<F>) return double(std::underlying_type_t<F>(value));
  else return double(value);
}

template <class S, class F>
double initialValue(F S::*field) {
  return toValue(S{}.*field);
}

}  // namespace key_table_detail

// A key declared elsewhere (radiusParameter, the shared denoisers' keys) bound to `field`; its
// default becomes the field's initial value.
template <class S, class F>
BoundKey<S> bindKey(F S::*field, Parameter parameter) {
  using namespace key_table_detail;
  parameter.defaultValue = initialValue(field);
  return {std::move(parameter), [field](S& s, double v) { s.*field = fromValue<F>(v); },
          [field](const S& s) { return toValue(s.*field); }};
}

// The run's radius (parameters.h), its fallback default the field's initial value.
template <class S>
BoundKey<S> radiusKey(float S::*field) {
  return bindKey(field, radiusParameter(key_table_detail::initialValue(field)));
}

template <class S>
BoundKey<S> floatKey(float S::*field, std::string key, double min, double max, std::string doc, bool tunable = false) {
  return bindKey(field, floatParameter(std::move(key), 0, min, max, std::move(doc), tunable));
}

template <class S>
BoundKey<S> intKey(int S::*field, std::string key, int min, int max, std::string doc, bool tunable = false) {
  return bindKey(field, intParameter(std::move(key), 0, min, max, std::move(doc), tunable));
}

template <class S>
BoundKey<S> boolKey(bool S::*field, std::string key, std::string doc) {
  return bindKey(field, boolParameter(std::move(key), false, std::move(doc)));
}

// `choices` name the enum's values in the order of their underlying integers 0, 1, ...
template <class S, class E>
BoundKey<S> enumKey(E S::*field, std::string key, std::vector<std::string> choices, std::string doc) {
  static_assert(std::is_enum_v<E>);
  return bindKey(field, enumParameter(std::move(key), std::move(choices), 0, std::move(doc)));
}

template <class S>
class KeyTable {
 public:
  KeyTable(std::initializer_list<BoundKey<S>> keys) : keys_(keys) {}

  // The technique's parameters, in the table's order.
  std::vector<Parameter> parameters() const {
    std::vector<Parameter> out;
    for (const auto& k : keys_) out.push_back(k.parameter);
    return out;
  }
  // S with the value of every key `settings` declares; the others keep S's initial values (for a
  // technique built on another's struct, such as reference on gtao's).
  S read(const Settings& settings) const {
    S s{};
    for (const auto& k : keys_)
      if (settings.has(k.parameter.key)) k.store(s, settings.value(k.parameter.key));
    return s;
  }
  // Settings of `technique` holding `values` for every key it declares; the others keep its defaults.
  Settings write(const Technique& technique, const S& values) const {
    Settings s(technique);
    for (const auto& k : keys_)
      if (s.has(k.parameter.key)) s.set(k.parameter.key, k.load(values));
    return s;
  }

 private:
  std::vector<BoundKey<S>> keys_;
};

}  // namespace aor
