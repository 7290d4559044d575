// The printable summary: inputs, results, the targets and the verdict, the figures, the engine version, the date
// and the thesis citation, laid out for A4 or Letter by print.css. Rebuilt after every computation.

import { governingText, liftTable, unitsTable } from "./combination.js";
import { $, clear, el, fmt } from "./dom.js";
import { factList, facts, srtText, targetsTable } from "./results.js";
import { radiusCaption, radiusTable } from "./road.js";

const RECORD_ORDER = [
  "weight_kn",
  "rear_track_m",
  "front_track_m",
  "rear_axle_width_m",
  "front_axle_width_m",
  "rear_axles",
  "front_axles",
  "rear_tires_per_axle",
  "front_tires_per_axle",
  "suspension_stiffness_kn_per_m",
  "tire_stiffness_kn_per_m",
  "fifth_wheel_stiffness_kn_per_m",
  "suspension_height_m",
  "rolling_radius_m",
  "fifth_wheel_height_m",
  "spring_separation_m",
  "fifth_wheel_width_m",
  "cg_height_above_chassis_m",
  "fifth_wheel_to_front_axle_m",
  "wheelbase_m",
  "front_axle_to_cg_m",
  "front_llt_ratio",
];

function caseRows(request) {
  const road = request.road || {};
  const load = request.load || {};
  const rows = [
    ["Model", `${request.model}${request.stage ? ` (stage ${request.stage})` : ""}`],
    ["Bank [%]", road.bank_percent],
    ["Grade [%] (+ uphill)", road.slope_percent],
    ["Trailer angle [deg]", request.trailer_angle_deg],
    ["Lateral CG offset d1 [m]", load.lateral_offset_m],
    ["Longitudinal CG offset d2 [m]", load.longitudinal_offset_m],
    ["Vertical CG offset d3 [m]", load.vertical_offset_m],
    ["Overweight [%]", load.overweight_percent],
    ["Rear LLT limit", request.rear_llt_limit],
  ];
  return rows.filter(([, v]) => v !== undefined).map(([k, v]) => [k, String(v)]);
}

/** The record's fields as a two-column list (on paper: two columns side by side). */
function recordList(record) {
  const rows = RECORD_ORDER.filter((k) => record[k] !== undefined && record[k] !== null).map((k) => [k, String(record[k])]);
  return el("dl", { class: "facts record" }, factList(rows));
}

function verdictLine(result) {
  const missed = result.targets.filter((t) => !t.meets);
  if (!missed.length) return `Verdict: the SRT of ${srtText(result.srt)} meets every target.`;
  return `Verdict: the SRT of ${srtText(result.srt)} is below ${missed.map((t) => `${t.name} (${srtText(t.target_g)})`).join(" and ")}.`;
}

/** Rebuild the summary from the last computation. */
export function update({ vehicle, request, result, figures, design, speed, link }) {
  const box = clear($("#summary-body"));
  const now = new Date();
  box.append(
    el(
      "p",
      {},
      `Computed ${now.toISOString().slice(0, 16).replace("T", " ")} UTC by rollover, engine version ${result.engine_version}. `,
      "Link: ",
      el("a", { href: link }, link),
    ),
    el("h3", {}, "Vehicle"),
    el("p", {}, vehicle.label),
    vehicle.record ? recordList(vehicle.record) : null,
    el("h3", {}, "Case"),
    el("dl", { class: "facts keep" }, factList(caseRows(request))),
    el("h3", {}, "Result"),
    el("p", { class: "srt-line" }, el("span", { class: "srt-label" }, "Static rollover threshold"), el("span", { class: "srt-value", id: "summary-srt" }, srtText(result.srt))),
    el("dl", { class: "facts keep" }, factList(facts(result))),
    el("h3", {}, "Targets"),
    el(
      "table",
      { class: "keep" },
      el("thead", {}, el("tr", {}, ["Target", "Minimum SRT [g]", "Verdict", "Margin [g]"].map((h) => el("th", { scope: "col" }, h)))),
      el("tbody", {}, targetsTable(result.targets)),
    ),
    el("p", { class: "verdict-line" }, verdictLine(result)),
  );
  if (result.roll_coupled_units?.length) {
    box.append(
      el("h3", {}, "Roll-coupled units"),
      el("p", { class: "verdict-line", id: "summary-governing" }, governingText(result)),
      el("div", { class: "keep" }, unitsTable(result)),
      el("h3", {}, "Lift-off sequence"),
      el("div", { class: "keep" }, liftTable(result)),
    );
  }
  if (figures.length) {
    box.append(el("h3", {}, "Curves against ay/g"), el("div", { class: "plots" }, figures.map((f) => f.cloneNode(true))));
  }
  if (speed) {
    box.append(el("h3", {}, "Curve speed"), el("p", {}, `Radius ${fmt(speed.radius_m, 1)} m: at most ${fmt(speed.max_speed_kmh, 1)} km/h (Eq. 9.1, SRT ${srtText(speed.srt)}).`));
  }
  if (design) {
    const fig = $("#road-results figure");
    box.append(
      el("h3", {}, "Minimum radius against design speed"),
      el("p", {}, radiusCaption(design)),
      el("div", { class: "radius-figure" }, fig ? fig.cloneNode(true) : null),
      el("div", { class: "keep" }, radiusTable(design.rows)),
    );
  }
}
