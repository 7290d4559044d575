// Reading the case from the form, and the page's state in its URL (a link reproduces a calculation).
//
// Every control with `data-param` is one URL query parameter of the same name as the API field it feeds
// (`bank_percent`, `rear_llt_limit`, `design_standard`, ...); a parameter is written only when the control
// differs from its initial value. The vehicle adds `vehicle` (preset or saved id), `record` or `spec` (JSON).

import { $, $$ } from "./dom.js";

/**
 * A control's value for a request: undefined when empty (the service's default applies), a number when it
 * reads as one ("0.5", "-4", "1e-3", "0,5"), else the text as typed -- so the service refuses it at its field.
 */
export function value(control) {
  if (!control || control.disabled) return undefined;
  const raw = control.value.trim();
  if (raw === "") return undefined;
  if (control.tagName === "SELECT") return control.dataset.int !== undefined ? Number(raw) : raw;
  const text = /^[-+]?(\d+[.,]?\d*|[.,]\d+)([eE][-+]?\d+)?$/.test(raw) ? raw.replace(",", ".") : null;
  return text === null ? raw : Number(text);
}

/** "general=0.35, dangerous_goods=0.4" (or name:value) -> {general: 0.35, ...}; throws on an entry without a name. */
export function parseTargets(text) {
  const raw = text.trim();
  if (!raw) return undefined;
  const out = {};
  for (const entry of raw.split(/[,;]\s*/).filter(Boolean)) {
    const m = entry.match(/^\s*([^=:\s]+)\s*[=:]\s*(.+?)\s*$/);
    if (!m) throw new Error(`"${entry}" is not name=value (e.g. general=0.35)`);
    const n = Number(m[2].replace(",", "."));
    out[m[1]] = m[2].trim() !== "" && Number.isFinite(n) ? n : m[2];
  }
  return out;
}

export const formatTargets = (targets) =>
  Object.entries(targets)
    .map(([k, v]) => `${k}:${v}`)
    .join(",");

const drop = (obj) => Object.fromEntries(Object.entries(obj).filter(([, v]) => v !== undefined));

/**
 * The SRT request fields of the case form other than the vehicle (controls the model does not take are
 * disabled and left out). `targets` parse errors are thrown with `control` set.
 */
export function caseFields() {
  const model = $("#model").value;
  let targets;
  try {
    targets = parseTargets($("#targets").value);
  } catch (err) {
    err.control = $("#targets");
    throw err;
  }
  return drop({
    model,
    stage: model === "3d" ? value($("#stage")) : undefined,
    road: drop({ bank_percent: value($("#bank")), slope_percent: value($("#slope")) }),
    trailer_angle_deg: value($("#trailer-angle")),
    load: drop({
      lateral_offset_m: value($("#d1")),
      longitudinal_offset_m: value($("#d2")),
      vertical_offset_m: value($("#d3")),
      overweight_percent: value($("#overweight")),
    }),
    rear_llt_limit: value($("#llt-limit")),
    targets,
  });
}

/** Remember each URL-state control's initial value (its default: not written to the URL). */
export function rememberDefaults() {
  for (const c of $$("[data-param]")) c.dataset.initial = c.value;
}

/** Set the URL-state controls from the query string; returns the URLSearchParams. */
export function applyParams(search = window.location.search) {
  const params = new URLSearchParams(search);
  for (const c of $$("[data-param]")) {
    const v = params.get(c.dataset.param);
    if (v === null) continue;
    if (c.tagName === "SELECT" && !Array.from(c.options).some((o) => o.value === v)) {
      c.dataset.pending = v; // options not loaded yet, or unknown: kept for when they are
      continue;
    }
    c.value = c.dataset.param === "targets" ? v.replaceAll(":", "=").replaceAll(",", ", ") : v;
  }
  return params;
}

/** The query string of the current state: the vehicle's parameters first, then every changed control. */
export function stateParams(vehicleParams) {
  const params = new URLSearchParams(vehicleParams);
  for (const c of $$("[data-param]")) {
    if (c.disabled || c.closest("[hidden]")) continue;
    if (c.value === c.dataset.initial) continue;
    let v = c.value.trim();
    if (c.dataset.param === "targets") {
      try {
        const t = parseTargets(v);
        v = t ? formatTargets(t) : "";
      } catch {
        /* keep as typed */
      }
    }
    params.set(c.dataset.param, v);
  }
  return params;
}

export function writeUrl(params) {
  const query = params.toString();
  const url = `${window.location.pathname}${query ? `?${query}` : ""}`;
  window.history.replaceState(null, "", url);
  return new URL(url, window.location.href).href;
}
