#pragma once

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/text_file.hpp"

namespace thetad {

// The version of what a plug-in shares with thetad: the Controller, ControlLaw and SdcPlant
// interfaces, Reference, ReferenceTrajectory and the factories' arguments. A registration records
// the version its plug-in was built against (its default argument is evaluated in the plug-in's
// code), and a registry refuses any other, so that an old plug-in is a clear error, not a crash
// mid-flight.
//   2: Reference has the commanded velocity and acceleration, ReferenceTrajectory their exact
//      values, SdcPlant the names of its states and inputs, its tracked states and its tracking
//      vector on the true state.
//   3: SdcPlant's feed-forward hooks (bias_state, commanded_motion, trim_source) and
//      ControllerContext's shared trims (docs/model.md §7.1).
//   4: ControlLaw's certificate columns and values (docs/model.md §8.4).
//   5: ControlLaw::last_iterations().
//   6: ControlLaw's log columns and values (log_columns, log_values), of which certificates are
//      those with a worst (they replace version 4's certificate columns).
inline constexpr int kPluginInterfaceVersion = 6;

// Where the registrations made while one lives come from: a plug-in being loaded ("plug-in
// /path/lib.so (sha256 ...)"); "built-in" outside one. Inside one a refused registration is kept
// for the loader (Registry::take_refusals), not thrown: it runs in the plug-in's static
// initialization, where an exception would end the program. Scopes nest; the end of one restores
// the origin before it.
class RegistrationOrigin {
 public:
  explicit RegistrationOrigin(std::string origin);
  ~RegistrationOrigin();
  RegistrationOrigin(const RegistrationOrigin&) = delete;
  RegistrationOrigin& operator=(const RegistrationOrigin&) = delete;

  static const std::string& current();
  static bool scoped();

 private:
  std::string previous_;
  bool previously_scoped_;
};

// Things thetad knows by name (controllers, plants), each registered from its own source file by a
// static registration, with its description, its origin and a factory: one set of rules for every
// kind, so a plug-in's plant is refused for what a plug-in's controller is.
template <class Factory>
class Registry {
 public:
  struct Entry {
    std::string name;
    std::string description;
    std::string origin;
    Factory factory;
  };

  // `kind` names the things in messages ("controller", "plant").
  explicit Registry(std::string kind) : kind_(std::move(kind)) {}

  // Refuses an empty or taken name and a plug-in built against another interface version: throws
  // thetad::Error, or inside a RegistrationOrigin keeps the refusal for take_refusals().
  void add(const std::string& name, const std::string& description, Factory factory, int interface_version) {
    std::string refusal;
    const auto taken = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.name == name; });
    if (interface_version != kPluginInterfaceVersion) {
      refusal = kind_ + " '" + escaped_utf8(name) + "' was built against plug-in interface version " +
                std::to_string(interface_version) + "; this thetad has version " +
                std::to_string(kPluginInterfaceVersion) + ": rebuild the plug-in against this thetad";
    } else if (name.empty()) {
      refusal = kind_ + " registry: an empty name (" + RegistrationOrigin::current() + ")";
    } else if (taken != entries_.end()) {
      refusal = kind_ + " registry: the name '" + escaped_utf8(name) + "' is registered twice (" + taken->origin +
                " and " + RegistrationOrigin::current() + ")";
    }
    if (refusal.empty()) {
      entries_.push_back({name, description, RegistrationOrigin::current(), std::move(factory)});
    } else if (RegistrationOrigin::scoped()) {
      refusals_.push_back(refusal);
    } else {
      throw Error(refusal);
    }
  }

  // Throws thetad::Error listing the known names when `name` is unknown.
  const Entry& entry(const std::string& name) const {
    for (const Entry& e : entries_) {
      if (e.name == name) return e;
    }
    throw Error("unknown " + kind_ + " '" + escaped_utf8(name) + "' (known: " +
                (entries_.empty() ? "none; a plug-in registers them" : known_names()) + ")");
  }
  bool contains(const std::string& name) const {
    return std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.name == name; });
  }
  // Sorted.
  std::vector<std::string> names() const {
    std::vector<std::string> result;
    for (const Entry& e : entries_) result.push_back(e.name);
    std::sort(result.begin(), result.end());
    return result;
  }
  // The names, sorted, comma separated: for "unknown" messages.
  std::string known_names() const {
    std::string known;
    for (const auto& n : names()) known += (known.empty() ? "" : ", ") + n;
    return known;
  }
  const std::string& description(const std::string& name) const { return entry(name).description; }
  // "built-in", or the RegistrationOrigin that `name` was registered in.
  const std::string& origin(const std::string& name) const { return entry(name).origin; }
  // The registrations refused inside a RegistrationOrigin since the last call, as messages.
  std::vector<std::string> take_refusals() { return std::exchange(refusals_, {}); }

 private:
  std::string kind_;
  std::vector<Entry> entries_;
  std::vector<std::string> refusals_;
};

}  // namespace thetad
