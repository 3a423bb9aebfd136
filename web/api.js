// What every panel of the page shares: the status line and the server's API. Every POST
// carries the session's token, which the server writes into the page (a page of another
// site cannot read it, so it cannot make the server edit, cook or save).
"use strict";

const $ = (id) => document.getElementById(id);

const TOKEN = document.querySelector('meta[name="cloudgraph-token"]')?.content ?? "";

function setStatus(text, isError = false) {
  $("status").textContent = text;
  $("status").classList.toggle("error", isError);
}

// GET `path`, or POST `body` as JSON. A refusal throws an Error with the server's message,
// its `status` and `conflict` (Save's 409 when the file changed on disk).
async function api(path, body) {
  const options = body === undefined ? {} : {
    method: "POST",
    headers: { "Content-Type": "application/json", "X-CloudGraph-Token": TOKEN },
    body: JSON.stringify(body),
  };
  const response = await fetch(path, options);
  const text = await response.text();
  let reply = {};
  try {
    reply = JSON.parse(text);
  } catch {
    if (response.ok) throw new Error(`${path}: the server's reply is not JSON`);
  }
  if (!response.ok) {
    const error = new Error(reply.error || text || response.statusText);
    error.status = response.status;
    error.conflict = reply.conflict === true;
    throw error;
  }
  return reply;
}
