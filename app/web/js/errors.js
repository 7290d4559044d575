// Problem details shown where they belong: each `errors[]` entry next to the control whose `data-field` is its
// dotted `field` (or, failing that, the nearest parent path: `vehicle.weight_kn` -> `vehicle`, then its last
// name: `curves.0.posted_speed_kmh` -> `posted_speed_kmh`); anything
// without a matching control in the section's form-level message.

import { ApiError } from "./api.js";
import { $, $$, el } from "./dom.js";

/** The API fields a control answers for: its `data-field`, a space-separated list of dotted names. */
const fieldsOf = (control) => control.dataset.field.split(" ");
const visible = (node) => node.offsetParent !== null || node.getClientRects().length > 0;

/** The visible control for a dotted API field inside `scope` (exact path first, then its parents). */
export function controlFor(dotted, scope = document) {
  const field = dotted.replace(/\[(\d+)\]/g, ".$1"); // the engine's spec.payloads[0].x is spec.payloads.0.x
  const candidates = [field];
  if (field.startsWith("vehicle.spec.")) candidates.push(field.slice("vehicle.".length));
  const parts = field.split(".");
  for (let n = parts.length - 1; n > 0; n -= 1) candidates.push(parts.slice(0, n).join("."));
  // a row's field of a table the request had no rows of (a route's `curves.0.posted_speed_kmh`): the field's name
  if (parts.length > 1) candidates.push(parts.at(-1));
  for (const name of candidates) {
    const exact = $$("[data-field]", scope).filter((c) => fieldsOf(c).includes(name) && visible(c));
    if (exact.length) return exact[0];
  }
  return null;
}

/** A control's name and unit from its label: "Radius [m]" -> ["Radius", "m"], "Posted speed [km/h] (where ...)" ->
 * ["Posted speed", "km/h"]. */
function nameOf(control) {
  const label = control.id ? $(`label[for="${control.id}"]`) : null;
  const text = (label?.textContent || control.getAttribute("aria-label") || "").trim();
  if (!text) return null;
  const m = text.match(/^(.*?)\s*\[([^\]]+)\]/); // the name before the unit, the unit in brackets
  return m ? [m[1].trim(), m[2]] : [text.replace(/\s*\(.*$/, "").trim(), ""];
}

/** The number in a framework message ("Input should be greater than or equal to 5" -> "5"). */
const numberIn = (message) => (String(message).match(/-?\d+(?:\.\d+)?/) || [null])[0];

/**
 * A field error in plain words with its unit and the value typed ("Radius must be at least 5 m; you typed -50"),
 * from the problem's `type` (the framework's error types, whose own words name neither) when the error is the
 * control's own; otherwise the service's message as it is (the engine's messages are in words already).
 */
export function plainMessage(item, control) {
  const named = control && nameOf(control);
  const own = control && fieldsOf(control).includes(item.field);
  if (!named || !own) return item.message;
  const [name, unit] = named;
  const typed = control.type === "file" ? "" : control.value.trim();
  const you = typed === "" ? "" : `; you typed ${typed}`;
  const n = numberIn(item.message);
  const u = unit ? ` ${unit}` : "";
  switch (item.type) {
    case "greater_than_equal":
      return `${name} must be at least ${n}${u}${you}`;
    case "greater_than":
      return `${name} must be more than ${n}${u}${you}`;
    case "less_than_equal":
      return `${name} must be at most ${n}${u}${you}`;
    case "less_than":
      return `${name} must be less than ${n}${u}${you}`;
    case "float_type":
    case "float_parsing":
    case "int_type":
    case "int_parsing":
    case "finite_number":
      return `${name} must be a number${unit ? ` (in ${unit})` : ""}${you}`;
    case "string_too_short":
      return typed === "" ? `${name} is needed: it cannot be empty` : `${name} is too short${you}`;
    case "string_too_long":
      return `${name} can be at most ${n} characters long; you typed ${typed.length}`;
    case "missing":
      return `${name} is needed`;
    default:
      return item.message;
  }
}

let counter = 0;

function markField(control, text) {
  const box = control.closest(".field") || control.parentElement;
  let note = box.querySelector(":scope > .field-error");
  if (!note) {
    note = el("p", { class: "field-error", id: `field-error-${(counter += 1)}` });
    box.append(note);
  }
  note.textContent = note.textContent ? `${note.textContent} ${text}` : text;
  control.setAttribute("aria-invalid", "true");
  const ids = new Set((control.getAttribute("aria-describedby") || "").split(" ").filter(Boolean));
  ids.add(note.id);
  control.setAttribute("aria-describedby", [...ids].join(" "));
  return note;
}

/** Remove every field and form message inside `scope`. */
export function clearErrors(scope) {
  for (const note of $$(".field-error", scope)) {
    const control = $$("[aria-describedby]", scope).find((c) => c.getAttribute("aria-describedby").includes(note.id));
    if (control) {
      const rest = control.getAttribute("aria-describedby").split(" ").filter((id) => id !== note.id);
      if (rest.length) control.setAttribute("aria-describedby", rest.join(" "));
      else control.removeAttribute("aria-describedby");
    }
    note.remove();
  }
  for (const c of $$('[aria-invalid="true"]', scope)) c.removeAttribute("aria-invalid");
  for (const box of $$(".form-error", scope)) {
    box.textContent = "";
    box.hidden = true;
  }
}

/**
 * Show an error inside `scope`: an ApiError's field errors at their controls, the rest in `formBox`.
 * Focuses the first offending control. Returns the number of field errors placed.
 */
export function showError(err, scope, formBox) {
  const problem = err instanceof ApiError ? err.problem : { title: "Error", detail: String(err.message || err) };
  const loose = [];
  let placed = 0;
  let first = null;
  for (const item of problem.errors || []) {
    const where = item.location ? ` (${item.location})` : "";
    const control = controlFor(item.field, scope) || controlFor(item.field, document);
    if (control) {
      const suffix = fieldsOf(control).includes(item.field) ? "" : ` [${item.field}]`;
      markField(control, `${plainMessage(item, control)}${where}${suffix}`);
      first ??= control;
      placed += 1;
    } else {
      loose.push(`${item.field}: ${item.message}${where}`);
    }
  }
  if (!placed || loose.length) {
    const head = problem.title ? `${problem.title}${problem.status ? ` (${problem.status})` : ""}` : "Error";
    const detail = loose.length ? loose.join("; ") : problem.detail || "";
    formBox.textContent = detail ? `${head}: ${detail}` : head;
    formBox.hidden = false;
  }
  if (first) first.focus({ preventScroll: false });
  return placed;
}

/** A page-local refusal (e.g. unreadable JSON) at one control. */
export function localError(control, message) {
  markField(control, message);
  control.focus();
}
