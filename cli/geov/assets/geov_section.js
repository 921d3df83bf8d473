// The environment towards the selected vehicle, on `acommsctl geov serve`'s
// page: the map server runs the buoy's model and draws it (the picture of
// `gram tl --png`, /api/section); the page shows it, or the server's reason
// for not having one. A vehicle is selected by clicking its marker or its row.
'use strict';
(function () {
  const page = window.geovPage;  // geov_map.js
  const { state, $, url, renderPanel } = page;

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

  page.selectVehicle = selectVehicle;
  page.loadSection = loadSection;
})();
