// The fleet map of `acommsctl geov serve`: the snapshot from /api/fleet,
// then every change from /events (server-sent events, resumed by id after a
// reconnect), playback of a chosen period from /api/history, and the
// transmission loss from the buoy towards a selected vehicle (/api/section,
// a PNG). Served from the binary with Leaflet; it loads nothing from
// elsewhere.
'use strict';
(function () {
  const token = new URLSearchParams(location.search).get('token');
  function url(path, query) {
    const q = new URLSearchParams(query || {});
    if (token) q.set('token', token);
    const s = q.toString();
    return path + (s ? '?' + s : '');
  }
  const colours = ['#d62728', '#1f77b4', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b'];
  const colour = (src) => colours[src % colours.length];
  // A position is [time, x, y, depth, lat, lon].
  const T = 0, X = 1, Y = 2, DEPTH = 3, LAT = 4, LON = 5;

  const state = {
    epoch: 0, id: 0, updates: 0, resets: 0, mode: 'live', connected: false,
    vehicles: new Map(), config: null, source: null,
    playback: { from: 0, to: 0, t: 0, playing: false, data: null, timer: null },
    section: { src: null, status: 0, bytes: 0, range_m: null, error: '', loads: 0, busy: false, url: null },
  };
  let map = null, useLatLon = false, grid = null, gridStep = 0;

  const $ = (id) => document.getElementById(id);
  function showError(text) { $('error').textContent = text || ''; }
  function setStatus(text, cls) { const s = $('status'); s.textContent = text; s.className = 'status ' + cls; }

  function toLatLng(p) { return useLatLon ? [p[LAT], p[LON]] : [p[Y], p[X]]; }
  function placeable(p) { return !useLatLon || (p[LAT] !== null && p[LON] !== null); }

  function setupMap(config) {
    useLatLon = !!config.tiles;
    if (useLatLon) {
      map = L.map('map', { zoomControl: true });
      L.tileLayer(url(config.tiles).replace(/%7B/g, '{').replace(/%7D/g, '}'),
                  { maxZoom: 20, attribution: config.attribution || '' }).addTo(map);
      map.setView([0, 0], 2);
    } else {
      // No network, no tiles: metres east (x) and north (y) of the datum.
      map = L.map('map', { crs: L.CRS.Simple, minZoom: -10, maxZoom: 5, zoomSnap: 0.25 });
      map.setView([0, 0], -2);
    }
  }

  // Grid lines and range rings around the datum, spaced 1, 2 or 5 x 10^k m
  // so that about four rings cover the fleet.
  function niceStep(range) {
    const raw = Math.max(range, 10) / 4;
    const k = Math.pow(10, Math.floor(Math.log10(raw)));
    return [1, 2, 5, 10].map((m) => m * k).find((s) => s >= raw);
  }
  function datumLatLng() {
    if (!useLatLon) return [0, 0];
    for (const v of state.vehicles.values()) {
      const p = v.track.length ? v.track[v.track.length - 1] : null;
      if (p && p[LAT] !== null) {
        const lat = p[LAT] - p[Y] / 111320;
        return [lat, p[LON] - p[X] / (111320 * Math.cos(lat * Math.PI / 180))];
      }
    }
    return null;
  }
  function drawGrid() {
    let range = 0;
    for (const v of state.vehicles.values()) {
      for (const p of v.track) range = Math.max(range, Math.hypot(p[X], p[Y]));
    }
    const step = niceStep(range);
    const centre = datumLatLng();
    if (!centre || (step === gridStep && grid)) return;
    if (grid) grid.remove();
    grid = L.layerGroup().addTo(map);
    gridStep = step;
    const rings = Math.ceil(range / step) + 1;
    for (let r = 1; r <= rings; ++r) {
      const ring = useLatLon ? L.circle(centre, { radius: r * step, color: '#888', weight: 1, fill: false })
                             : L.circle(centre, { radius: r * step, color: '#888', weight: 1, fill: false });
      ring.addTo(grid);
      // Labelled at the ring's north point, where a view of the fleet most
      // often has it.
      const label = useLatLon ? [centre[0] + r * step / 111320, centre[1]] : [r * step, 0];
      L.tooltip({ permanent: true, direction: 'right', className: 'geov-ring-label' })
        .setLatLng(label).setContent((r * step) + ' m').addTo(grid);
    }
    if (!useLatLon) {
      const edge = rings * step;
      for (let g = -edge; g <= edge; g += step) {
        L.polyline([[g, -edge], [g, edge]], { color: '#ccc', weight: 1, interactive: false }).addTo(grid);
        L.polyline([[-edge, g], [edge, g]], { color: '#ccc', weight: 1, interactive: false }).addTo(grid);
      }
      L.circleMarker([0, 0], { radius: 4, color: '#000', weight: 1 }).bindTooltip('datum').addTo(grid);
    }
  }

  function arrowIcon(src, heading) {
    const rotate = heading === null ? 0 : heading;
    const shape = heading === null ? '<circle cx="0" cy="0" r="6"/>' : '<path d="M0,-10 L6,8 L0,4 L-6,8 Z"/>';
    return L.divIcon({
      className: 'geov-marker geov-marker-' + src, iconSize: [20, 20], iconAnchor: [10, 10],
      html: '<svg width="20" height="20" viewBox="-10 -10 20 20"><g transform="rotate(' + rotate + ')" fill="' +
            colour(src) + '" stroke="#000" stroke-width="1">' + shape + '</g></svg>',
    });
  }

  function vehicle(src) {
    let v = state.vehicles.get(src);
    if (!v) {
      v = { src: src, track: [], summary: {}, line: null, marker: null };
      state.vehicles.set(src, v);
    }
    return v;
  }

  // Appends positions newer than the last; an older one (a back-fill) is
  // put in its place, a repeated time ignored.
  function addPositions(v, added) {
    for (const p of added) {
      const n = v.track.length;
      if (n === 0 || p[T] > v.track[n - 1][T]) { v.track.push(p); continue; }
      let i = n - 1;
      while (i >= 0 && v.track[i][T] > p[T]) --i;
      if (i >= 0 && v.track[i][T] === p[T]) continue;
      v.track.splice(i + 1, 0, p);
    }
  }

  function draw(v, upTo) {
    if (!map) return;
    let track = v.track;
    if (upTo !== undefined) track = track.filter((p) => p[T] <= upTo);
    track = track.filter(placeable);
    const points = track.map(toLatLng);
    if (!v.line) {
      v.line = L.polyline(points, { color: colour(v.src), weight: 2, className: 'geov-track geov-track-' + v.src })
        .addTo(map);
    } else {
      v.line.setLatLngs(points);
    }
    if (!points.length) {
      if (v.marker) { v.marker.remove(); v.marker = null; }
      return;
    }
    const last = points[points.length - 1];
    let heading = null;
    if (track.length >= 2) {
      const a = track[track.length - 2], b = track[track.length - 1];
      if (a[X] !== b[X] || a[Y] !== b[Y]) heading = (Math.atan2(b[X] - a[X], b[Y] - a[Y]) * 180 / Math.PI + 360) % 360;
    }
    if (!v.marker) {
      v.marker = L.marker(last, { icon: arrowIcon(v.src, heading) }).bindTooltip('node ' + v.src).addTo(map);
      v.marker.on('click', () => selectVehicle(v.src));
    } else {
      v.marker.setLatLng(last);
      v.marker.setIcon(arrowIcon(v.src, heading));
    }
  }

  function age(seconds) {
    if (!seconds) return '–';
    const s = Math.max(0, Date.now() / 1000 - seconds);
    return s < 120 ? s.toFixed(0) + ' s' : s < 7200 ? (s / 60).toFixed(0) + ' min' : (s / 3600).toFixed(1) + ' h';
  }
  const fixed = (x, d) => (x === null || x === undefined ? '–' : Number(x).toFixed(d));

  function renderPanel() {
    const rows = [];
    for (const v of [...state.vehicles.values()].sort((a, b) => a.src - b.src)) {
      const s = v.summary, last = s.last;
      const where = !last ? '–' : last[LAT] !== null ? fixed(last[LAT], 5) + ', ' + fixed(last[LON], 5)
                                                     : fixed(last[X], 0) + ', ' + fixed(last[Y], 0) + ' m';
      const link = s.link || {};
      const queued = (s.queued || []).map((q) => q.type + (q.in_flight ? ' (in flight)' : '')).join('\n');
      rows.push('<tr data-src="' + v.src + '"' + (v.src === state.section.src ? ' class="selected"' : '') + '><td><span class="swatch" style="background:' + colour(v.src) +
                '"></span>' + v.src + '</td><td>' + where + '</td><td>' + fixed(s.heading, 0) + '</td><td>' +
                (last ? fixed(last[DEPTH], 1) : '–') + '</td><td>' + (last ? age(last[T]) : '–') + '</td><td>' +
                fixed(link.snr_in_db, 1) + '</td><td>' + (s.link ? link.rate : '–') + '</td><td>' +
                age(s.last_heard) + '</td><td title="' + queued.replace(/"/g, '&quot;') + '">' +
                (s.queued_count || 0) + '</td></tr>');
    }
    document.querySelector('#vehicles tbody').innerHTML = rows.join('');
  }

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

  // The view takes in the whole fleet when a vehicle first appears, and
  // again when a vehicle's last position leaves it; otherwise pan and zoom
  // stay where the operator put them.
  const fitted = new Set();
  function fit() {
    const all = [];
    let refit = false;
    const view = map.getBounds();
    for (const v of state.vehicles.values()) {
      const points = v.track.filter(placeable);
      if (points.length && !fitted.has(v.src)) { refit = true; fitted.add(v.src); }
      if (points.length && !view.contains(toLatLng(points[points.length - 1]))) refit = true;
      for (const p of points) all.push(toLatLng(p));
    }
    if (refit && all.length) map.fitBounds(L.latLngBounds(all).pad(0.3), { animate: false });
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

  // ---- the environment towards the selected vehicle: the server runs the
  // buoy's model and draws it (the picture of `gram tl --png`); the page
  // shows it, or the server's reason for not having one.
  function selectVehicle(src) {
    state.section.src = src;
    $('section-node').textContent = 'towards node ' + src;
    renderPanel();
    loadSection();
  }
  async function loadSection() {
    const sec = state.section;
    if (sec.src === null || sec.busy) return;
    sec.busy = true;
    const src = sec.src;
    try {
      const response = await fetch(url('/api/section', { src: src }));
      sec.status = response.status;
      if (!response.ok) {
        sec.error = response.status + ': ' + (await response.text()).trim();
        sec.bytes = 0;
        $('section-note').textContent = sec.error;
        $('section-img').hidden = true;
        return;
      }
      const blob = await response.blob();
      if (sec.url) URL.revokeObjectURL(sec.url);
      sec.url = URL.createObjectURL(blob);
      sec.bytes = blob.size;
      sec.error = '';
      sec.range_m = Number(response.headers.get('X-Acomms-Range-M'));
      sec.loads += 1;
      $('section-img').src = sec.url;
      $('section-img').hidden = false;
      $('section-note').textContent = 'node ' + src + ' is ' + sec.range_m.toFixed(0) +
        ' m from the buoy (drawn ' + new Date().toISOString().slice(11, 19) + ' UTC)';
    } catch (e) {
      sec.error = String(e.message || e);
      $('section-note').textContent = sec.error;
    } finally {
      sec.busy = false;
    }
  }

  // ---- playback of a chosen period: the operator's start and end (UTC),
  // checked by the server, which names what is wrong with them.
  const toInput = (t) => new Date(t * 1000).toISOString().slice(0, 19);
  const fromInput = (text) => (text ? Date.parse(text + (text.length === 16 ? ':00Z' : 'Z')) / 1000 : NaN);
  function recentPeriod() {
    const to = Date.now() / 1000;
    $('pb-from').value = toInput(to - 600);
    $('pb-to').value = toInput(to);
    kmlHistoryLink();
  }
  function playbackRange() {
    if (!$('pb-from').value || !$('pb-to').value) recentPeriod();
    return { from: fromInput($('pb-from').value), to: fromInput($('pb-to').value) };
  }
  function kmlHistoryLink() {
    const r = state.mode === 'playback' ? state.playback : playbackRange();
    if (!isFinite(r.from) || !isFinite(r.to)) return;
    $('kml-history').href = url('/kml/history.kml', { from: r.from.toFixed(3), to: r.to.toFixed(3) });
  }
  function heldSpan() {
    let first = Infinity, last = -Infinity;
    for (const v of state.vehicles.values()) {
      if (!v.track.length) continue;
      first = Math.min(first, v.track[0][T]);
      last = Math.max(last, v.track[v.track.length - 1][T]);
    }
    $('pb-held').textContent = isFinite(first) ? 'positions held from ' + toInput(first) + ' to ' + toInput(last) + ' UTC' : '';
  }
  async function startPlayback() {
    const r = playbackRange();
    if (!isFinite(r.from) || !isFinite(r.to)) { showError('playback: give a start and an end'); return; }
    const response = await fetch(url('/api/history', { from: r.from.toFixed(3), to: r.to.toFixed(3) }));
    if (!response.ok) { showError('playback: ' + (await response.text()).trim()); return; }
    showError('');
    const history = await response.json();
    const pb = state.playback;
    pb.from = history.from; pb.to = history.to; pb.t = history.from;
    pb.data = new Map(history.vehicles.map((h) => [h.src, h.track]));
    state.mode = 'playback';
    setStatus('playback', 'playback');
    kmlHistoryLink();
    resumePlayback();
  }
  function resumePlayback() {
    const pb = state.playback;
    pb.playing = true;
    $('pb-play').textContent = 'Pause';
    let wall = performance.now();
    clearInterval(pb.timer);
    pb.timer = setInterval(() => {
      const now = performance.now();
      pb.t = Math.min(pb.to, pb.t + (now - wall) / 1000 * Number($('pb-speed').value));
      wall = now;
      renderPlayback();
      if (pb.t >= pb.to) pausePlayback();
    }, 100);
  }
  function pausePlayback() {
    const pb = state.playback;
    pb.playing = false;
    clearInterval(pb.timer);
    $('pb-play').textContent = 'Play';
  }
  function renderPlayback() {
    const pb = state.playback;
    for (const v of state.vehicles.values()) {
      const shown = { src: v.src, track: pb.data.get(v.src) || [], line: v.line, marker: v.marker };
      draw(shown, pb.t);
      v.line = shown.line;
      v.marker = shown.marker;
    }
    $('pb-time').textContent = new Date(pb.t * 1000).toISOString().replace(/\.\d+Z/, 'Z') + '  (' +
                               ((pb.t - pb.from) / 60).toFixed(1) + ' of ' + ((pb.to - pb.from) / 60).toFixed(1) + ' min)';
    $('pb-slider').value = String(Math.round(1000 * (pb.t - pb.from) / Math.max(1e-9, pb.to - pb.from)));
  }
  function goLive() {
    pausePlayback();
    state.mode = 'live';
    setStatus(state.connected ? 'live' : 'reconnecting', state.connected ? 'live' : 'down');
    $('pb-time').textContent = 'live';
    $('pb-slider').value = '1000';
    for (const v of state.vehicles.values()) draw(v);
  }

  function wireControls() {
    $('pb-play').onclick = () => {
      if (state.mode !== 'playback') startPlayback();
      else if (state.playback.playing) pausePlayback();
      else resumePlayback();
    };
    $('pb-live').onclick = goLive;
    $('pb-slider').oninput = () => {
      if (state.mode !== 'playback') return;
      const pb = state.playback;
      pb.t = pb.from + (pb.to - pb.from) * Number($('pb-slider').value) / 1000;
      renderPlayback();
    };
    $('pb-from').onchange = kmlHistoryLink;
    $('pb-to').onchange = kmlHistoryLink;
    $('pb-recent').onclick = recentPeriod;
    $('section-img').onclick = () => { if (state.section.url) window.open(state.section.url); };  // full size
    document.querySelector('#vehicles tbody').onclick = (e) => {
      const row = e.target.closest('tr[data-src]');
      if (row) selectVehicle(Number(row.dataset.src));
    };
    $('kml-live').href = url('/kml/network.kml');
    recentPeriod();
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
