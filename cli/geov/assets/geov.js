// The page of `acommsctl geov serve`, live: the snapshot from /api/fleet,
// then every change from /events (server-sent events, resumed by id after a
// reconnect), the controls wired, and what a test can ask the page
// (window.geov). Served from the binary with Leaflet; it loads nothing from
// elsewhere.
'use strict';
(function () {
  // The page's parts, loaded before this file: geov_map.js (the map and the
  // panel), geov_section.js (the environment), geov_playback.js.
  const page = window.geovPage;
  const { state, $, url, showError, setStatus, T, setupMap, drawGrid, vehicle, addPositions, draw, renderPanel, fit,
          selectVehicle, loadSection, startPlayback, heldSpan, wirePlaybackControls } = page;

  function applySummary(v, summary) {
    const copy = Object.assign({}, summary);
    delete copy.track;
    delete copy.added;
    v.summary = copy;
  }

  function applySnapshot(snapshot) {
    state.epoch = snapshot.epoch;
    state.id = snapshot.id;
    for (const s of snapshot.vehicles) {
      const v = vehicle(s.src);
      v.track = [];
      addPositions(v, s.track);
      applySummary(v, s);
    }
    if (state.mode === 'live') { drawGrid(); for (const v of state.vehicles.values()) draw(v); fit(); }
    renderPanel();
  }

  function applyUpdate(id, update) {
    state.id = id;
    state.updates += 1;
    const known = state.vehicles.has(update.src);
    const v = vehicle(update.src);
    if (!known) setTimeout(renderPanel, 0);  // a new row at once, not at the next tick
    addPositions(v, update.added);
    applySummary(v, update);
    if (state.mode === 'live') { drawGrid(); draw(v); fit(); }
  }

  async function loadSnapshot() {
    const response = await fetch(url('/api/fleet'));
    if (!response.ok) throw new Error('/api/fleet: ' + response.status + ' ' + (await response.text()));
    applySnapshot(await response.json());
  }

  // The stream, resumed after the last update applied. EventSource itself
  // reconnects with Last-Event-ID after a dropped connection; when it gives
  // up (an HTTP error while the server restarts), the page starts a new one.
  function openStream() {
    if (state.source) state.source.close();
    const source = new EventSource(url('/events', { after: state.epoch + ':' + state.id }));
    state.source = source;
    source.onopen = () => { state.connected = true; showError(''); setStatus(state.mode, state.mode); };
    source.onmessage = (e) => {
      const id = Number(String(e.lastEventId).split(':')[1]);
      applyUpdate(id, JSON.parse(e.data));
    };
    source.addEventListener('reset', () => {
      // This server does not hold what came after our last update (it
      // restarted, or we were away long): reload everything.
      state.resets += 1;
      source.close();
      loadSnapshot().then(openStream, retryLater);
    });
    source.onerror = () => {
      state.connected = false;
      setStatus('reconnecting', 'down');
      if (source.readyState === EventSource.CLOSED) retryLater();
    };
  }
  function retryLater(error) {
    if (error) showError(String(error.message || error));
    state.connected = false;
    setStatus('reconnecting', 'down');
    setTimeout(() => connectAll().catch(retryLater), 2000);
  }

  function wireControls() {
    wirePlaybackControls();
    $('section-img').onclick = () => { if (state.section.url) window.open(state.section.url); };  // full size
    document.querySelector('#vehicles tbody').onclick = (e) => {
      const row = e.target.closest('tr[data-src]');
      if (row) selectVehicle(Number(row.dataset.src));
    };
    $('kml-live').href = url('/kml/network.kml');
  }

  // What a test (or a curious operator, in the console) can ask the page.
  window.geov = {
    state: state,
    startPlayback: startPlayback,
    selectVehicle: selectVehicle,
    summary: () => ({
      error: $('error').textContent,
      section: { src: state.section.src, status: state.section.status, bytes: state.section.bytes,
                 range_m: state.section.range_m, error: state.section.error, loads: state.section.loads },
      mode: state.mode, connected: state.connected, epoch: state.epoch, id: state.id, updates: state.updates,
      resets: state.resets, playback: { from: state.playback.from, to: state.playback.to, t: state.playback.t,
                                        playing: state.playback.playing },
      vehicles: [...state.vehicles.values()].map((v) => ({
        src: v.src, positions: v.track.length, drawn: v.line ? v.line.getLatLngs().length : 0,
        marker: v.marker ? [v.marker.getLatLng().lat, v.marker.getLatLng().lng] : null,
        last_time: v.track.length ? v.track[v.track.length - 1][T] : null,
      })),
    }),
  };

  // The map needs the server's config (tiles or a metric grid) first, then
  // the snapshot, then the stream; after a failure, whatever is missing.
  async function connectAll() {
    if (!state.config) {
      const response = await fetch(url('/api/config'));
      if (!response.ok) throw new Error('/api/config: ' + response.status + ' ' + (await response.text()));
      state.config = await response.json();
      setupMap(state.config);
    }
    if (!state.epoch) await loadSnapshot();
    openStream();
  }

  function main() {
    wireControls();
    connectAll().catch(retryLater);
    setInterval(() => { if (state.mode === 'live') { renderPanel(); heldSpan(); } }, 1000);
    // The vehicle moves: its section is asked for again (the server reuses
    // its picture while the vehicle is about where it was).
    setInterval(() => { if (state.mode === 'live') loadSection(); }, 30000);
  }
  main();
})();
