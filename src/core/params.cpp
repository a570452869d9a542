#include "abu/core/params.hpp"

#include <charconv>
#include <cmath>
#include <fmt/format.h>

namespace abu {

std::string_view to_string(FrictionLaw law) {
  switch (law) {
    case FrictionLaw::none: return "none";
    case FrictionLaw::viscous: return "viscous";
    case FrictionLaw::coulomb: return "coulomb";
    case FrictionLaw::stribeck: return "stribeck";
    case FrictionLaw::lugre: return "lugre";
    case FrictionLaw::coulomb_set: return "coulomb-set";
  }
  return "?";
}

std::optional<FrictionLaw> friction_law_from_string(std::string_view name) {
  for (auto law : {FrictionLaw::none, FrictionLaw::viscous, FrictionLaw::coulomb, FrictionLaw::stribeck,
                   FrictionLaw::lugre, FrictionLaw::coulomb_set})
    if (to_string(law) == name) return law;
  return std::nullopt;
}

namespace {
struct SymbolEntry {
  std::string_view symbol;
  Quantity quantity;
  std::string_view unit;
};
// One spelling for CLI, scene overrides and CSV headers (model.md §1 symbols).
constexpr std::array<SymbolEntry, 20> kSymbols{{
    {"omega", Quantity::omega, "rad/s"},
    {"U", Quantity::unbalance, "kg m"},
    {"k", Quantity::stiffness, "N/m"},
    {"c", Quantity::damping, "N s/m"},
    {"M_r", Quantity::rotor_mass, "kg"},
    {"m", Quantity::ball_mass, "kg"},
    {"l", Quantity::race_radius, "m"},
    {"r", Quantity::ball_radius, "m"},
    {"mu", Quantity::mu, "-"},
    {"d", Quantity::d, "N s/m"},
    {"mu_c", Quantity::mu_c, "-"},
    {"mu_s", Quantity::mu_s, "-"},
    {"v_s", Quantity::v_s, "rad/s"},
    {"sigma0", Quantity::sigma0, "1/rad"},
    {"sigma1", Quantity::sigma1, "s/rad"},
    {"sigma2", Quantity::sigma2, "s/rad"},
    {"kappa", Quantity::kappa, "s/rad"},
    {"rho", Quantity::density, "kg/m^3"},
    {"f", Quantity::rolling_length, "m"},
    {"R_s", Quantity::surface_radius, "m"},
}};

const SymbolEntry& entry(Quantity q) {
  for (const auto& e : kSymbols)
    if (e.quantity == q) return e;
  return kSymbols[0];
}
}  // namespace

bool is_per_ball(Quantity q) {
  switch (q) {
    case Quantity::ball_mass:
    case Quantity::race_radius:
    case Quantity::ball_radius:
    case Quantity::mu:
    case Quantity::d:
    case Quantity::mu_c:
    case Quantity::mu_s:
    case Quantity::v_s:
    case Quantity::sigma0:
    case Quantity::sigma1:
    case Quantity::sigma2:
    case Quantity::density:
    case Quantity::rolling_length:
    case Quantity::surface_radius: return true;
    default: return false;
  }
}

bool acts_through_specification(Quantity q) {
  return q == Quantity::ball_radius || q == Quantity::density || q == Quantity::rolling_length ||
         q == Quantity::surface_radius;
}

std::optional<ParamRef> parse_param(std::string_view symbol, int n_balls) {
  for (const auto& e : kSymbols)
    if (e.symbol == symbol) return ParamRef{e.quantity, -1};
  // Per-ball form: a per-ball symbol followed by a 1-based index, e.g. "m2", "mu_c1".
  std::size_t digits = symbol.size();
  while (digits > 0 && symbol[digits - 1] >= '0' && symbol[digits - 1] <= '9') --digits;
  if (digits == symbol.size() || digits == 0 || symbol[digits] == '0') return std::nullopt;
  int index = 0;
  const auto* first = symbol.data() + digits;
  const auto* last = symbol.data() + symbol.size();
  if (auto [ptr, ec] = std::from_chars(first, last, index); ec != std::errc() || ptr != last) return std::nullopt;
  if (index < 1 || index > n_balls) return std::nullopt;
  const auto base = symbol.substr(0, digits);
  for (const auto& e : kSymbols)
    if (e.symbol == base && is_per_ball(e.quantity)) return ParamRef{e.quantity, index - 1};
  return std::nullopt;
}

std::string to_string(ParamRef ref) {
  const auto& e = entry(ref.quantity);
  if (ref.ball < 0) return std::string(e.symbol);
  return fmt::format("{}{}", e.symbol, ref.ball + 1);
}

std::string_view unit(Quantity q) { return entry(q).unit; }

std::string_view param_symbols_help() {
  return "omega U k c M_r kappa (global); m l r mu d mu_c mu_s v_s sigma0 sigma1 sigma2 rho f R_s (every ball) or "
         "with a 1-based ball index: m1 m2 l1 l2 mu1 mu2 ...";
}

bool law_uses(FrictionLaw law, Quantity q) {
  switch (q) {
    case Quantity::mu:
    case Quantity::rolling_length: return law == FrictionLaw::coulomb || law == FrictionLaw::coulomb_set;
    case Quantity::d: return law == FrictionLaw::viscous;
    case Quantity::mu_c:
    case Quantity::mu_s:
    case Quantity::v_s: return law == FrictionLaw::stribeck || law == FrictionLaw::lugre;
    case Quantity::sigma0:
    case Quantity::sigma1:
    case Quantity::sigma2: return law == FrictionLaw::lugre;
    case Quantity::kappa: return law == FrictionLaw::coulomb || law == FrictionLaw::stribeck;
    default: return true;
  }
}


template <class T, int N>
T get(const ParamsT<T, N>& p, ParamRef ref) {
  switch (ref.quantity) {
    case Quantity::omega: return p.omega;
    case Quantity::unbalance: return p.rotor.unbalance;
    case Quantity::stiffness: return p.rotor.stiffness;
    case Quantity::damping: return p.rotor.damping;
    case Quantity::rotor_mass: return p.rotor.mass;
    case Quantity::kappa: return p.kappa;
    default: return ball_field(p.balls[std::size_t(ref.ball < 0 ? 0 : ref.ball)], ref.quantity);
  }
}

template <class T, int N>
void set(ParamsT<T, N>& p, ParamRef ref, T value) {
  switch (ref.quantity) {
    case Quantity::omega: p.omega = value; return;
    case Quantity::unbalance: p.rotor.unbalance = value; return;
    case Quantity::stiffness: p.rotor.stiffness = value; return;
    case Quantity::damping: p.rotor.damping = value; return;
    case Quantity::rotor_mass: p.rotor.mass = value; return;
    case Quantity::kappa: p.kappa = value; return;
    default:
      if (ref.ball >= 0) {
        set_ball(p.balls[std::size_t(ref.ball)], ref.quantity, value);
      } else {
        for (auto& b : p.balls) set_ball(b, ref.quantity, value);
      }
  }
}

template double get<double, 2>(const ParamsT<double, 2>&, ParamRef);
template double get<double, any_balls>(const ParamsT<double, any_balls>&, ParamRef);
template long double get<long double, any_balls>(const ParamsT<long double, any_balls>&, ParamRef);
template void set<double, any_balls>(ParamsT<double, any_balls>&, ParamRef, double);
template void set<long double, any_balls>(ParamsT<long double, any_balls>&, ParamRef, long double);
template double get<double, 3>(const ParamsT<double, 3>&, ParamRef);
template long double get<long double, 2>(const ParamsT<long double, 2>&, ParamRef);
template void set<double, 2>(ParamsT<double, 2>&, ParamRef, double);
template void set<double, 3>(ParamsT<double, 3>&, ParamRef, double);
template void set<long double, 2>(ParamsT<long double, 2>&, ParamRef, long double);

std::optional<std::string> range_violation(Quantity q, double value) {
  if (!std::isfinite(value)) return fmt::format("must be a finite number (got {})", value);
  switch (q) {
    case Quantity::omega:
    case Quantity::stiffness:
    case Quantity::rotor_mass:
    case Quantity::ball_mass:
    case Quantity::race_radius:
    case Quantity::ball_radius:
    case Quantity::kappa:
    case Quantity::v_s:
    case Quantity::sigma0:
    case Quantity::density:
    case Quantity::surface_radius:
      if (!(value > 0.0)) return fmt::format("must be > 0 (got {})", value);
      return std::nullopt;
    case Quantity::unbalance:
    case Quantity::damping:
    case Quantity::mu:
    case Quantity::d:
    case Quantity::mu_c:
    case Quantity::mu_s:
    case Quantity::sigma1:
    case Quantity::sigma2:
    case Quantity::rolling_length:
      if (value < 0.0) return fmt::format("must be >= 0 (got {})", value);
      return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace abu
