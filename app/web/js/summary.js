// The printable summary: inputs, results, the targets and the verdict, the figures, the engine version, the date
// and the thesis citation, laid out for A4 or Letter by print.css. Rebuilt after every computation.

import { COUPLINGS, governingText, KINDS, liftTable, unitsTable } from "./combination.js";
import { $, clear, el, fmt, grouped, num, table, thousands } from "./dom.js";
import { factList, facts, plainVerdicts, showsLevelRoad, srtText, targetsTable } from "./results.js";
import { bankWords, radiusCaption, radiusTable } from "./road.js";

/** The record's fields in words, with the thesis symbol and the unit (the weight W as a mass in kg). */
const RECORD_FIELDS = [
  ["weight_kn", "Mass (weight W / g)", "kg", (v) => (v * 1000) / 9.81, 0],
  ["rear_track_m", "Rear track (t3)", "m"],
  ["front_track_m", "Front track (t1)", "m"],
  ["rear_axle_width_m", "Rear axle width (t4)", "m"],
  ["front_axle_width_m", "Front axle width (t2)", "m"],
  ["rear_axles", "Rear axles", ""],
  ["front_axles", "Front axles", ""],
  ["rear_tires_per_axle", "Rear tyres per axle", ""],
  ["front_tires_per_axle", "Front tyres per axle", ""],
  ["suspension_stiffness_kn_per_m", "Suspension stiffness per axle (kLs)", "kN/m"],
  ["tire_stiffness_kn_per_m", "Tyre stiffness per tyre (kT)", "kN/m"],
  ["fifth_wheel_stiffness_kn_per_m", "Fifth-wheel stiffness (kf)", "kN/m"],
  ["suspension_height_m", "Suspension height (ls)", "m"],
  ["rolling_radius_m", "Rolling radius (lr)", "m"],
  ["fifth_wheel_height_m", "Fifth-wheel height (lf)", "m"],
  ["spring_separation_m", "Spring separation (b)", "m"],
  ["fifth_wheel_width_m", "Fifth-wheel width (b1)", "m"],
  ["cg_height_above_chassis_m", "CG height above the chassis (l12)", "m"],
  ["fifth_wheel_to_front_axle_m", "Fifth wheel to front axle (l13)", "m"],
  ["wheelbase_m", "Wheelbase (L)", "m"],
  ["front_axle_to_cg_m", "Front axle to CG (a)", "m"],
  ["front_llt_ratio", "Front LLT ratio at the limit (LLTf/LLTr)", ""],
];

const withUnit = (value, unit, digits = 3) => `${thousands(num(value, digits))}${unit ? ` ${unit}` : ""}`;

/** A model by its name (the model picker's words), not its id. */
const modelName = (id) => Array.from($("#model")?.options || []).find((o) => o.value === id)?.textContent || id;
const STAGES = { full: "full system", "tires-suspension": "tyres and suspension only" };

function caseRows(request) {
  const road = request.road || {};
  const load = request.load || {};
  const rows = [
    ["Bank (superelevation)", road.bank_percent, "%"],
    ["Grade (+ uphill)", road.slope_percent, "%"],
    ["Trailer angle", request.trailer_angle_deg, "deg"],
    ["Lateral CG offset (d1, + outward)", load.lateral_offset_m, "m"],
    ["Longitudinal CG offset (d2, + forward)", load.longitudinal_offset_m, "m"],
    ["Vertical CG offset (d3, + up)", load.vertical_offset_m, "m"],
    ["Overweight", load.overweight_percent, "%"],
    ["Rear LLT limit (1 = wheel lift-off)", request.rear_llt_limit, ""],
  ];
  return [
    ["Model", `${modelName(request.model)}${request.stage ? ` (${STAGES[request.stage] || request.stage})` : ""}`],
    ...rows.filter(([, v]) => v !== undefined).map(([k, v, unit]) => [k, typeof v === "number" ? withUnit(v, unit, 4) : String(v)]),
  ];
}

/** The record's fields in words with units (on paper: two columns side by side). */
function recordList(record) {
  const rows = RECORD_FIELDS.filter(([k]) => record[k] !== undefined && record[k] !== null).map(([k, label, unit, convert, digits]) => [
    label,
    withUnit(convert ? convert(record[k]) : record[k], unit, digits ?? 3),
  ]);
  return el("dl", { class: "facts record" }, factList(rows));
}

/** A combination's units and couplings in words: masses in kg, heights in m. */
function combinationList(combination) {
  const units = table(
    [
      { key: "id", label: "Unit", text: true },
      { key: "kind", label: "Kind", text: true, format: (v) => KINDS[v] || v },
      { key: "sprung_mass_kg", label: "Sprung mass [kg]", format: (v) => grouped(v, 0) },
      { key: "cg_height_m", label: "CG height [m]", format: (v) => fmt(v, 2) },
      { key: "groups", label: "Axle groups", text: true, format: (g) => g.map((x) => `${x.id}: ${x.axles} axle${x.axles > 1 ? "s" : ""}, ${x.tyres_per_axle} tyres each`).join("; ") },
    ],
    combination.units,
  );
  const couplings = combination.couplings.map((c, i) => `${COUPLINGS[c.kind] || c.kind} between ${combination.units[i]?.id} and ${combination.units[i + 1]?.id}, ${fmt(c.height_m, 2)} m high`);
  return [el("div", { class: "keep" }, units), el("ul", {}, couplings.map((c) => el("li", {}, c)))];
}

/** A copy of a node of the page without its ids (the page keeps them). */
function copyWithoutIds(node) {
  const copy = node.cloneNode(true);
  if (copy.removeAttribute) copy.removeAttribute("id");
  for (const n of copy.querySelectorAll?.("[id]") || []) n.removeAttribute("id");
  return copy;
}

function verdictLines(result) {
  return plainVerdicts(result).map((v) => v.text).join(" ");
}

/** Rebuild the summary from the last computation. */
export function update({ vehicle, request, result, figures, design, speed, link }) {
  const box = clear($("#summary-body"));
  const now = new Date();
  const add = (...nodes) => box.append(...nodes.flat().filter(Boolean));
  add(
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
    vehicle.combination ? combinationList(vehicle.combination) : null,
    el("h3", {}, "Case"),
    el("dl", { class: "facts keep" }, factList(caseRows(request))),
    el("h3", {}, "Result"),
    showsLevelRoad(result)
      ? el("p", { class: "srt-line" }, el("span", { class: "srt-label" }, "Level-road SRT (judged against targets)"), el("span", { class: "srt-value" }, srtText(result.level_road_srt)))
      : null,
    el(
      "p",
      { class: "srt-line" },
      el("span", { class: "srt-label" }, showsLevelRoad(result) ? "This curve's threshold with its bank and grade" : "Static rollover threshold"),
      el("span", { class: "srt-value", id: "summary-srt" }, srtText(result.srt)),
    ),
    el("p", { class: "verdict-line" }, `Verdict: ${verdictLines(result)}`),
    result.roll_coupled_units?.length ? el("p", { class: "verdict-line", id: "summary-governing" }, governingText(result)) : null,
    el("h3", {}, "At the limit (the thesis's notation)"),
    el("dl", { class: "facts keep" }, factList(facts(result))),
    el("h3", {}, "Targets"),
    el(
      "table",
      { class: "keep" },
      el("thead", {}, el("tr", {}, ["Target", "Minimum SRT [g]", "Verdict", "Margin [g]"].map((h) => el("th", { scope: "col" }, h)))),
      el("tbody", {}, targetsTable(result.targets)),
    ),
  );
  if (result.roll_coupled_units?.length) {
    box.append(
      el("h3", {}, "Roll-coupled units"),
      el("div", { class: "keep" }, unitsTable(result)),
      el("h3", {}, "Lift-off sequence"),
      el("div", { class: "keep" }, liftTable(result)),
    );
  }
  if (figures.length) {
    box.append(el("h3", {}, "Curves against ay/g"), el("div", { class: "plots" }, figures.map((f) => f.cloneNode(true))));
  }
  if (speed) {
    box.append(
      el("h3", { class: "with-next" }, "Curve speed"),
      el("p", {}, `Radius ${fmt(speed.radius_m, 0)} m ${bankWords(request)}: at most ${fmt(speed.max_speed_kmh, 1)} km/h (Eq. 9.1, SRT ${srtText(speed.srt)}).`),
    );
    // the same curve's advisory speed, by method, when a posted speed was typed
    const advised = $("#advisory-result");
    if (advised?.childNodes.length) box.append(el("div", { class: "advisory-print" }, Array.from(advised.childNodes).map(copyWithoutIds)));
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

/**
 * A part of the page printed after the summary when it is shown (the superelevation table, the payload table, the
 * route or alignment): `nodes` are copied (moved when `owned`); null removes the part. `lead`: a node printed at
 * the top of the summary too (a road's counts and worst curve, so the first page says what the road's part holds).
 */
export function extra(name, title, nodes, { lead = null, owned = false } = {}) {
  const box = $("#summary-extras");
  box.querySelector(`[data-extra="${name}"]`)?.remove();
  $(`#summary-lead [data-extra="${name}"]`)?.remove();
  if (!nodes) return;
  const part = el("section", { "data-extra": name, class: `summary-extra extra-${name}` }, el("h3", { class: "with-next" }, title));
  // `owned`: nodes built for the printout only are moved, not copied (a road's table can hold 500 rows)
  for (const node of nodes.filter(Boolean)) part.append(owned ? node : node.cloneNode(true));
  for (const id of part.querySelectorAll("[id]")) id.removeAttribute("id");
  box.append(part);
  if (lead) {
    const top = el("section", { "data-extra": name, class: "summary-lead-part" }, el("h3", {}, `${title} assessed (its curves follow)`), lead.cloneNode(true));
    for (const id of top.querySelectorAll("[id]")) id.removeAttribute("id");
    $("#summary-lead").append(top);
  }
}
