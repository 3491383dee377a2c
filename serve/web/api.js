// SPDX-License-Identifier: BSD-3-Clause
// The page's only way to the server: the JSON API of docs/serve.md.

/** Throws an Error carrying the server's one-line reason for any status other than 2xx. */
async function reply(response) {
  const body = await response.json().catch(() => ({}));
  if (!response.ok) {
    const error = new Error(body.error || `HTTP ${response.status}`);
    error.status = response.status;
    error.body = body;
    throw error;
  }
  return body;
}

export async function getJSON(url) {
  return reply(await fetch(url));
}

export async function postJSON(url, body) {
  return reply(await fetch(url, {
    method: 'POST',
    headers: {'Content-Type': 'application/json'},
    body: JSON.stringify(body),
  }));
}

export async function upload(file) {
  const url = '/api/scenes?name=' + encodeURIComponent(file.name);
  return reply(await fetch(url, {method: 'POST', body: file}));
}

/**
 * Starts a job (a search, a check, a plan) and follows it to its end, calling onProgress with
 * {fraction, message} as it runs; its result, or an Error with the job's reason.
 */
export async function runJob(url, body, onProgress) {
  const started = await postJSON(url, body);
  for (;;) {
    // A long poll: the server answers as soon as the job ends, or after 0.3 s.
    const job = await getJSON(`/api/jobs/${started.job}?wait=0.3`);
    if (onProgress) onProgress(job.progress);
    if (job.state === 'done') return job.result;
    if (job.state === 'failed') throw new Error(job.error);
  }
}
