// The page's only way to the service: the public HTTP API, same origin. Errors are RFC 9457 problem details
// (application/problem+json) thrown as ApiError; the OpenAPI document says which operations this deployment has.

export class ApiError extends Error {
  /** @param {object} problem the problem details (type, title, status, detail, errors[{field, message, loc}]) */
  constructor(problem) {
    super(problem.detail || problem.title || `HTTP ${problem.status}`);
    this.problem = problem;
  }
}

let specPromise = null;

/** The service's OpenAPI document (read once). */
export function spec() {
  specPromise ??= fetch("/openapi.json", { headers: { Accept: "application/json" } })
    .then((r) => (r.ok ? r.json() : { paths: {} }))
    .catch(() => ({ paths: {} }));
  return specPromise;
}

/** Whether this deployment has an operation, e.g. has("post", "/v1/vehicles/build"). */
export async function has(method, path) {
  const doc = await spec();
  return Boolean(doc.paths?.[path]?.[method.toLowerCase()]);
}

/** The JSON schema of an operation's JSON request body (refs resolved one level), or null. */
export async function requestSchema(method, path) {
  const doc = await spec();
  const op = doc.paths?.[path]?.[method.toLowerCase()];
  let schema = op?.requestBody?.content?.["application/json"]?.schema ?? null;
  if (schema?.$ref) schema = doc.components?.schemas?.[schema.$ref.split("/").pop()] ?? null;
  return schema;
}

async function problemOf(response) {
  const type = response.headers.get("content-type") || "";
  if (type.includes("json")) {
    try {
      return await response.json();
    } catch {
      /* not JSON after all */
    }
  }
  return { status: response.status, title: response.statusText || `HTTP ${response.status}` };
}

/**
 * One request. `json` is sent as the JSON body (a Blob: as it is, JSON already); `accept` is the wanted media type; `key` a bearer key.
 * Returns {response, data}: data is parsed JSON, text (SVG, CSV) or a Blob (`as: "blob"`).
 */
export async function call(method, path, { json, accept = "application/json", key, as, signal } = {}) {
  const headers = { Accept: accept };
  if (json !== undefined) headers["Content-Type"] = "application/json";
  if (key) headers.Authorization = `Bearer ${key}`;
  let response;
  try {
    response = await fetch(path, {
      method,
      headers,
      body: json === undefined ? undefined : json instanceof Blob ? json : JSON.stringify(json),
      signal,
      credentials: "omit",
    });
  } catch (err) {
    throw new ApiError({ status: 0, title: "The service did not answer", detail: String(err.message || err) });
  }
  if (!response.ok) throw new ApiError(await problemOf(response));
  if (as === "blob") return { response, data: await response.blob() };
  const type = response.headers.get("content-type") || "";
  const data = type.includes("json") ? await response.json() : await response.text();
  return { response, data };
}

export const get = async (path, opts) => (await call("GET", path, opts)).data;
export const post = async (path, json, opts) => (await call("POST", path, { ...opts, json })).data;
export const postSvg = (path, json) => post(path, json, { accept: "image/svg+xml" });
