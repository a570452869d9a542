#include "abu/io/report.hpp"

#include <fmt/format.h>

#include <cmath>

#include "abu/io/io.hpp"

namespace abu {

namespace {

std::string num(double v, std::string_view what) { return format_number(v, what); }

std::string eigenvalue_cells(const Spectrum& sp) {
  std::string s;
  for (int k = 0; k < Spectrum::size; ++k) {
    const auto& l = sp.eigenvalues[std::size_t(k)];
    s += fmt::format(",{},{}", num(l.real(), "eigenvalue"), num(l.imag(), "eigenvalue"));
  }
  return s;
}

std::string eigenvalue_header() {
  std::string s;
  for (int k = 1; k <= Spectrum::size; ++k) s += fmt::format(",re{},im{}", k, k);
  return s;
}

std::string label(const Equilibrium& e) { return fmt::format("{} {}", to_string(e.family), e.member); }

// Notes on one equilibrium that a reader of the numbers must know.
std::vector<std::string> notes(const Equilibrium& e, const Spectrum& sp) {
  std::vector<std::string> out;
  if (e.is_set) out.push_back("representative of a circle of equilibria (U = 0)");
  if (!e.converged) out.push_back(fmt::format("Newton polish did not converge (residual {:.3g})", e.residual));
  if (!sp.converged) out.push_back("an eigenvalue refinement did not converge; its error estimate is the QR bound");
  if (sp.stability == Stability::marginal)
    out.push_back(fmt::format("marginal: {} eigenvalue(s) within the error band of the imaginary axis", sp.n_marginal));
  if (sp.ill_conditioned) {
    double worst = 0;
    for (double c : sp.condition) worst = std::max(worst, c);
    out.push_back(fmt::format("ill-conditioned spectrum: condition number up to {:.3g} (input rounding alone "
                              "moves an eigenvalue by > 1e-8 of its modulus)", worst));
  }
  return out;
}

double q_abs(const Equilibrium& e) { return std::hypot(double(e.position(0)), double(e.position(1))); }

std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          out += fmt::format("\\u{:04x}", int(c));
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

}  // namespace

std::string_view equilibrium_columns_doc() {
  return "# columns: family = balanced|together|opposite (model.md §5); q1, q2 [m] rotor centre in the "
         "rotating frame; beta1, beta2 [rad] ball angles from the unbalance, in [0, 2 pi);\n"
         "#   residual = max_i |b_i(s,0)| / scale_i, dimensionless (rounding level ~1e-16); "
         "spectral_abscissa = max Re lambda [1/s];\n"
         "#   stable = 1 if every eigenvalue lies left of its error band around the imaginary axis, else 0;\n"
         "#   re_k, im_k [1/s] eigenvalue k of the 8x8 Jacobian (state order q1 q2 beta1 beta2 and their rates), "
         "sorted by real part descending, then imaginary part descending\n";
}

std::string equilibria_csv(const Analysis& a, std::string_view header) {
  std::string out(header);
  out += equilibrium_columns_doc();
  for (const auto& line : describe_degeneracy(a.equilibria.degeneracy)) out += fmt::format("# degenerate: {}\n", line);
  const auto points = a.equilibria.points();
  for (std::size_t i = 0; i < points.size(); ++i)
    for (const auto& n : notes(points[i], a.spectra[i])) out += fmt::format("# {}: {}\n", label(points[i]), n);
  out += "family,q1,q2,beta1,beta2,residual,spectral_abscissa,stable" + eigenvalue_header() + "\n";
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& e = points[i];
    const auto& sp = a.spectra[i];
    out += fmt::format("{},{},{},{},{},{},{},{}{}\n", to_string(e.family), num(double(e.position(0)), "q1"),
                       num(double(e.position(1)), "q2"), num(double(e.position(2)), "beta1"),
                       num(double(e.position(3)), "beta2"), num(e.residual, "residual"),
                       num(sp.abscissa, "spectral abscissa"), sp.stability == Stability::stable ? 1 : 0,
                       eigenvalue_cells(sp));
  }
  return out;
}

std::string equilibria_json(const Analysis& a, std::string_view command_line, std::string_view scene_file,
                            const Params& p) {
  std::string out = fmt::format("{{\n  \"program\": \"stability-scan {}\",\n  \"command\": {},\n  \"scene\": {},\n",
                                ABU_VERSION, json_string(command_line), json_string(scene_file));
  out += fmt::format("  \"parameters\": {},\n  \"units\": {},\n", json_string(describe_parameters(p)),
                     json_string("q [m], beta [rad] in [0, 2 pi), eigenvalues and errors [1/s], residual and "
                                 "condition dimensionless"));
  out += "  \"degeneracies\": [";
  const auto deg = describe_degeneracy(a.equilibria.degeneracy);
  for (std::size_t i = 0; i < deg.size(); ++i) out += (i ? ", " : "") + json_string(deg[i]);
  out += "],\n  \"equilibria\": [";
  const auto points = a.equilibria.points();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& e = points[i];
    const auto& sp = a.spectra[i];
    out += i ? ",\n    {" : "\n    {";
    out += fmt::format("\"family\": \"{}\", \"member\": {}, \"q1\": {}, \"q2\": {}, \"beta1\": {}, \"beta2\": {}, ",
                       to_string(e.family), e.member, num(double(e.position(0)), "q1"),
                       num(double(e.position(1)), "q2"), num(double(e.position(2)), "beta1"),
                       num(double(e.position(3)), "beta2"));
    out += fmt::format("\"q_abs\": {}, \"residual\": {}, \"newton_iterations\": {}, \"converged\": {}, "
                       "\"is_set\": {},\n     ",
                       num(q_abs(e), "|q|"), num(e.residual, "residual"), e.newton_iterations, e.converged,
                       e.is_set);
    out += fmt::format("\"stability\": \"{}\", \"spectral_abscissa\": {}, \"n_unstable\": {}, \"n_marginal\": {}, "
                       "\"ill_conditioned\": {}, \"spectrum_converged\": {},\n     \"eigenvalues\": [",
                       to_string(sp.stability), num(sp.abscissa, "abscissa"), sp.n_unstable, sp.n_marginal,
                       sp.ill_conditioned, sp.converged);
    for (std::size_t k = 0; k < Spectrum::size; ++k) {
      out += fmt::format("{}{{\"re\": {}, \"im\": {}, \"error\": {}, \"condition\": {}}}", k ? ",\n       " : "",
                         num(sp.eigenvalues[k].real(), "eigenvalue"), num(sp.eigenvalues[k].imag(), "eigenvalue"),
                         num(sp.error[k], "error"),
                         std::isfinite(sp.condition[k]) ? num(sp.condition[k], "condition") : std::string("null"));
    }
    out += "]}";
  }
  out += "\n  ]\n}\n";
  return out;
}

std::string equilibria_table(const Analysis& a, const Params& p) {
  const double omega_n = std::sqrt(p.rotor.stiffness / p.total_mass());
  std::string out = fmt::format("omega = {} rad/s = {:.4f} omega_n (omega_n = {:.6g} rad/s), friction {}\n",
                                p.omega, p.omega / omega_n, omega_n, to_string(p.law));
  for (const auto& line : describe_degeneracy(a.equilibria.degeneracy)) out += fmt::format("degenerate: {}\n", line);
  const auto points = a.equilibria.points();
  if (points.empty()) out += "no equilibria\n";
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& e = points[i];
    const auto& sp = a.spectra[i];
    out += fmt::format("\n{:<11} q = ({:.9g}, {:.9g}) m, |q| = {:.6g} m, beta = ({:.12g}, {:.12g}) rad\n", label(e),
                       double(e.position(0)), double(e.position(1)), q_abs(e), double(e.position(2)),
                       double(e.position(3)));
    out += fmt::format("{:<11} residual {:.2g}, {} Newton steps; {}, spectral abscissa {:.9g} 1/s, {} unstable\n", "",
                       e.residual, e.newton_iterations, to_string(sp.stability), sp.abscissa, sp.n_unstable);
    out += fmt::format("{:<11} {:>24} {:>24} {:>10} {:>10}\n", "", "Re lambda [1/s]", "Im lambda [1/s]", "cond",
                       "error");
    for (std::size_t k = 0; k < Spectrum::size; ++k)
      out += fmt::format("{:<11} {:>24.15g} {:>24.15g} {:>10.3g} {:>10.2g}\n", "", sp.eigenvalues[k].real(),
                         sp.eigenvalues[k].imag(), sp.condition[k], sp.error[k]);
    for (const auto& n : notes(e, sp)) out += fmt::format("{:<11} note: {}\n", "", n);
  }
  return out;
}

std::string sweep_csv(const SweepResult& s, std::string_view header) {
  const std::string name = to_string(s.param);
  std::string out(header);
  out += fmt::format("# sweep of {} [{}] over {} values; step = index of the value\n", name,
                     unit(s.param.quantity), s.values.size());
  out += equilibrium_columns_doc();
  out += "#   member = which root of the family's closed form (1 or 2); q_abs = |q| [m]; n_unstable = eigenvalues "
         "right of their error band\n";
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const auto& a = s.points[i];
    for (const auto& line : describe_degeneracy(a.equilibria.degeneracy))
      out += fmt::format("# at {}={}: degenerate: {}\n", name, s.values[i], line);
    const auto points = a.equilibria.points();
    for (std::size_t k = 0; k < points.size(); ++k)
      for (const auto& n : notes(points[k], a.spectra[k]))
        out += fmt::format("# at {}={}: {}: {}\n", name, s.values[i], label(points[k]), n);
  }
  out += fmt::format("step,{},family,member,q1,q2,beta1,beta2,q_abs,residual,spectral_abscissa,stable,n_unstable{}\n",
                     name, eigenvalue_header());
  for (auto family : {Family::balanced, Family::together, Family::opposite}) {
    for (int member = 1; member <= 2; ++member) {
      for (std::size_t i = 0; i < s.points.size(); ++i) {
        const auto& a = s.points[i];
        const auto points = a.equilibria.points();
        for (std::size_t k = 0; k < points.size(); ++k) {
          const auto& e = points[k];
          if (e.family != family || e.member != member) continue;
          const auto& sp = a.spectra[k];
          out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}{}\n", i, num(s.values[i], name),
                             to_string(family), member, num(double(e.position(0)), "q1"),
                             num(double(e.position(1)), "q2"), num(double(e.position(2)), "beta1"),
                             num(double(e.position(3)), "beta2"), num(q_abs(e), "|q|"), num(e.residual, "residual"),
                             num(sp.abscissa, "spectral abscissa"), sp.stability == Stability::stable ? 1 : 0,
                             sp.n_unstable, eigenvalue_cells(sp));
        }
      }
    }
  }
  return out;
}

std::string analysis_warnings(const Analysis& a, std::string_view where) {
  std::string out;
  const auto points = a.equilibria.points();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& e = points[i];
    if (!e.converged)
      out += fmt::format("warning: {}: {}: Newton polish did not converge (residual {:.3g})\n", where, label(e),
                         e.residual);
    if (!a.spectra[i].converged)
      out += fmt::format("warning: {}: {}: eigenvalue refinement did not converge\n", where, label(e));
  }
  return out;
}

}  // namespace abu
