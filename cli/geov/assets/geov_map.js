// The map of `acommsctl geov serve`'s page: Leaflet over tiles, or a metric
// grid with range rings around the fleet's datum when there is no network;
// each vehicle's track and heading marker; the panel's table. The page's
// other parts (geov_section.js, geov_playback.js, and geov.js: the live
// stream) draw through these functions. They share one namespace,
// window.geovPage, which this file, loaded first, makes.
'use strict';
(function () {
  const page = window.geovPage = {};
  const token = new URLSearchParams(location.search).get('token');
  // A path on the map server, with the page's token when it came with one.
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
      v.marker.on('click', () => page.selectVehicle(v.src));  // geov_section.js
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

  Object.assign(page, {
    url, state, $, showError, setStatus, T, X, Y, DEPTH, LAT, LON, setupMap, drawGrid, vehicle, addPositions, draw,
    renderPanel, fit,
  });
})();
