// Files of `stability-scan outcomes` (docs/model.md §21): one CSV row per run, the statistics as
// JSON, and the answer in words for the terminal, the dry verdict first. They format a study;
// they compute nothing.
//
//   std::string csv = abu::outcomes_csv(study, header);
//   std::string json = abu::outcomes_json(study, command_line, scene_file);
#pragma once

#include <string>
#include <string_view>

#include "abu/analysis/outcomes.hpp"

namespace abu {

/// `header`, then `sample,beta1_0..betan_0,<uncertain names>,outcome,residual_q,bare_rotor_q,
/// balls_fixed_q,ratio_bare,ratio_fixed,peak_q,peak_q_run_up,stalled,settle_time,
/// stuck_off_balance,steps` [m, s]; a figure a run does not have is empty (never NaN). Only
/// the runs done.
std::string outcomes_csv(const OutcomeStudy& s, std::string_view header);

/// The study, its design and inputs, and every statistic with its interval (null where the
/// sample cannot bound it) and proportion with Wilson's interval.
std::string outcomes_json(const OutcomeStudy& s, std::string_view command_line, std::string_view scene_file);

/// A quantile and its interval in words, `scale` applied (1e6 for µm): "12.3 µm [11.9, 12.8]", "-"
/// for a side the sample does not bound.
std::string interval_text(const QuantileEstimate& q, double scale, std::string_view unit);

/// The answer in words: the verdict line, then the residual against the bare rotor and the
/// balls held, the peak, how the runs ended, the settle time (µm, s).
std::string outcomes_text(const OutcomeStudy& s);

}  // namespace abu
