// Section 3: the SRT result (POST /v1/srt) and the curves against ay/g (POST /v1/plots/*, the service's SVGs).

import * as api from "./api.js";
import { $, clear, el, fieldLabel, fmt, num, signed, svgNode } from "./dom.js";

export const PLOTS = [
  { path: "/v1/plots/tire-loads", caption: "Tire loads Fz1, Fz3, Fz17, Fz19 against ay/g (thesis Figs. 85-87, 92)" },
  { path: "/v1/plots/llt", caption: "Lateral load transfer LLTf, LLTr against ay/g (Fig. 93)" },
  { path: "/v1/plots/roll", caption: "Total roll angle against ay/g (Fig. 94)" },
  { path: "/v1/plots/cg-path", caption: "CG path h1, h2 against ay/g (Figs. 96-97)" },
];

/** "0.339 g": the SRT as the page shows it everywhere (three decimals). */
export const srtText = (srt) => `${fmt(srt, 3)} g`;

export function verdict(check) {
  return el("span", { class: check.meets ? "verdict pass" : "verdict fail" }, check.meets ? "\u2713 meets" : "\u2717 below");
}

/** A target's name in words: "dangerous_goods" -> "dangerous goods". */
export const targetName = (name) => name.replaceAll("_", " ");

/** Whether the answer has a level-road SRT that differs (as shown) from the case's own threshold. */
export const showsLevelRoad = (result) =>
  typeof result.level_road_srt === "number" && fmt(result.level_road_srt, 3) !== fmt(result.srt, 3);

/**
 * The verdict in plain words, one sentence per target: "Below the 0.35 g general target by 0.011 g." /
 * "Meets the 0.40 g dangerous goods target by 0.012 g." (what it is judged on when that is the level-road SRT).
 */
export function plainVerdicts(result) {
  const level = showsLevelRoad(result);
  return result.targets.map((t) => {
    const by = Math.abs(t.margin_g);
    const amount = fmt(by, 3) === "0.000" ? "by less than 0.001 g" : `by ${fmt(by, 3)} g`;
    const what = `the ${num(t.target_g, 3, 2)} g ${targetName(t.name)} target`;
    const on = level && (t.judged_on === "level_road_srt" || t.judged_on === undefined) ? " (on the level-road SRT)" : "";
    return { meets: t.meets, text: t.meets ? `Meets ${what} ${amount}${on}.` : `Below ${what} ${amount}${on}.` };
  });
}

export function targetsTable(checks) {
  const body = checks.map((c) =>
    el("tr", {}, el("td", {}, targetName(c.name)), el("td", {}, fmt(c.target_g, 3)), el("td", {}, verdict(c)), el("td", {}, signed(c.margin_g, 3))),
  );
  return body;
}

/** The list of the result's facts: [label, text] pairs (shared with the printed summary). */
export function facts(result) {
  const rows = [];
  const sv = result.stage_values || {};
  if ("srt_ts" in sv) rows.push(["SRT_ts (tyres and suspension)", srtText(sv.srt_ts)]);
  if ("srt_3d" in sv) rows.push(["SRT_3D (full system)", srtText(sv.srt_3d)]);
  rows.push(["Tilt-table angle atan(SRT)", `${fmt(result.tilt_table_angle_deg, 2)}\u00b0`]);
  if (result.roll_angle_deg !== null) rows.push(["Roll angle at the limit", `${fmt(result.roll_angle_deg, 2)}\u00b0`]);
  if (result.llt_front !== null) rows.push(["LLT front (LLTf)", fmt(result.llt_front, 3)]);
  if (result.llt_rear !== null) rows.push(["LLT rear (LLTr)", fmt(result.llt_rear, 3)]);
  if (result.cg_lateral_m !== null) rows.push(["CG lateral h1", `${fmt(result.cg_lateral_m, 3)} m`]);
  if (result.cg_height_m !== null) rows.push(["CG height h2", `${fmt(result.cg_height_m, 3)} m`]);
  const tl = result.tire_loads;
  if (tl) {
    const parts = [
      ["Fz1", tl.front_outer_kn],
      ["Fz3", tl.front_inner_kn],
      ["Fz17", tl.rear_outer_kn],
      ["Fz19", tl.rear_inner_kn],
    ].filter(([, v]) => v !== null);
    rows.push(["Tire loads [kN]", parts.map(([k, v]) => `${fieldLabel(k, true).replace(" [kN]", "")} ${fmt(v, 1)}`).join(", ")]);
  }
  rows.push(["Limit", `${result.limit} (rear LLT limit ${num(result.rear_llt_limit, 3)})`]);
  return rows;
}

export function factList(rows) {
  return rows.flatMap(([k, v]) => [el("dt", {}, k), el("dd", {}, v)]);
}

export function showResult(result, modelInfo) {
  $("#results-empty").hidden = true;
  $("#results-body").hidden = false;
  const out = $("#srt-value");
  out.textContent = srtText(result.srt);
  out.dataset.srt = String(result.srt);
  out.title = `SRT = ${result.srt} g`;
  // judged on the level road: both thresholds, each labelled, when the case's bank or grade changes it
  const level = showsLevelRoad(result);
  $("#level-srt-line").hidden = !level;
  $("#level-srt-value").textContent = level ? srtText(result.level_road_srt) : "";
  $("#srt-label").textContent = level ? "This curve's threshold with its bank and grade" : "Static rollover threshold";
  $("#bar-srt").textContent = srtText(level ? result.level_road_srt : result.srt);
  const verdicts = plainVerdicts(result);
  clear($("#verdict-plain")).append(...verdicts.map((v) => el("li", { class: v.meets ? "pass" : "fail" }, el("span", { class: v.meets ? "verdict pass" : "verdict fail" }, v.meets ? "\u2713" : "\u2717"), " ", v.text)));
  const missed = verdicts.filter((v) => !v.meets).length;
  $("#bar-verdict").textContent = missed ? `below ${missed} of ${verdicts.length} targets` : verdicts.length ? "meets every target" : "";
  $("#bar-verdict").className = missed ? "verdict fail" : "verdict pass";
  const stage = result.stage ? `, stage ${result.stage}` : "";
  $("#srt-context").textContent = `${modelInfo ? modelInfo.name : result.model} (${result.model}${stage}); engine ${result.engine_version}.`;
  clear($("#targets-table tbody")).append(...targetsTable(result.targets));
  clear($("#result-facts")).append(...factList(facts(result)));
  clear($("#result-notes")).append(...result.notes.map((n) => el("li", {}, n)));
  showWarnings($("#result-warnings"), result.warnings);
  $("#engine-version").textContent = result.engine_version;
}

/**
 * The answer's input warnings (a typed value that reads plausibly in another unit too: a light trailer's 50 kN, or
 * 50 t typed as kN) in the service's own words, each with the field as the request names it; the box hides when
 * there are none.
 */
export function showWarnings(box, warnings) {
  const list = warnings || [];
  box.hidden = !list.length;
  clear(box.querySelector("ul")).append(...list.map((w) => el("li", {}, el("code", {}, w.field), `: ${w.message}`)));
}

/** Draw the curves of the case (2d and 3d models); returns the figures (for the summary). */
export async function showPlots(request, hasCurves) {
  const box = clear($("#plots"));
  $("#plots-none").hidden = hasCurves;
  if (!hasCurves) return [];
  const figures = PLOTS.map((p) => {
    const fig = el("figure", { class: "plot", "aria-busy": "true" }, el("figcaption", {}, p.caption));
    box.append(fig);
    return fig;
  });
  await Promise.all(
    PLOTS.map(async (p, i) => {
      try {
        const svg = svgNode(await api.postSvg(p.path, request));
        figures[i].prepend(svg);
      } catch (err) {
        figures[i].append(el("p", { class: "form-error" }, `The figure could not be drawn: ${err.message}`));
      } finally {
        figures[i].setAttribute("aria-busy", "false");
      }
    }),
  );
  return figures;
}
