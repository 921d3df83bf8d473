// Playback of a chosen period on `acommsctl geov serve`'s page: the
// operator's start and end (UTC), checked by the server (/api/history), which
// names what is wrong with them; a speed and a slider; the KML history link
// of the same period.
'use strict';
(function () {
  const page = window.geovPage;  // geov_map.js
  const { state, $, url, draw, showError, setStatus, T } = page;

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

  function wirePlaybackControls() {
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
    recentPeriod();
  }

  Object.assign(page, { startPlayback, heldSpan, wirePlaybackControls });
})();
