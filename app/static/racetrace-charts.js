// racetrace: plotly charts whose library is loaded after the first 3-D frame (see app/lazy_charts.py).
//
// Registers <racetrace-chart>, a stand-in for trame-plotly's <TramePlotly> that shows a short
// "loading" line until window.racetrace_charts.load(url) has fetched the trame-plotly bundle, then
// renders the real chart with the same attributes (data, layout, displayModeBar, ...).
//
// A chart that follows the time also gets an `overlay` ({data: [traces], shapes: [shapes]}: what
// marks the current frame, sent with the frames) besides its figure (`data`, `layout`: sent once per
// result and option). The chart shows the figure's traces then the overlay's, and the figure's
// layout with the overlay's shapes after its own (app.charts.merge_overlay does the same in Python).
// A new figure (or new overlay traces) is drawn whole, with the marks of now, by trame-plotly's
// react(). A new overlay of shapes only (each played frame) moves the marks alone: plotly's
// relayout() of the layout's shapes, which supplies the shapes' defaults and draws the shapes and
// nothing else, where react() supplies the defaults of the whole figure and compares it with the
// one shown. The marks move at the next animation frame after a change, once for all the overlays
// given meanwhile, to the last one given (a paused chart shows the marks of the frame on show).
// The figure's typed arrays (plotly JSON's {dtype, bdata, shape}) are decoded here once per figure:
// plotly decodes them again at every update otherwise, and new arrays make it recompute and redraw
// every trace.
//
// Each chart first draws in a task of its own, after the task that ran the bundle (one chart a
// task, in the order they asked): the bundle's run and a chart's first drawing take a second or
// more each on a loaded machine in headless Chromium, and in one task (the bundle's onload set the
// component, and Vue mounted every chart before the task ended) they held the page's main thread
// for 4-10 s, during which a follower's page took no frame (app.serve.coalesce).
(function () {
  const { defineComponent, h, shallowRef, markRaw, watch, nextTick, onUpdated, onBeforeUnmount } =
    window.Vue;
  const chart = shallowRef(null); // the TramePlotly component once its bundle has run
  let requested = false;
  const turns = []; // charts waiting for their task to draw first, oldest first
  let releasing = false;

  function releaseNext() {
    const show = turns.shift();
    if (show) show();
    nextTick(function () {  // once Vue has drawn this one: the next in a later task
      if (turns.length) setTimeout(releaseNext, 0);
      else releasing = false;
    });
  }

  // show() in a later task of its own, after those that asked before it
  function inTurn(show) {
    turns.push(show);
    if (!releasing) {
      releasing = true;
      setTimeout(releaseNext, 0);
    }
  }

  function load(url) {
    if (requested) return;
    requested = true;
    const script = document.createElement("script");
    script.src = url;
    script.onload = function () {
      const found = {};
      window.trame_plotly.install({
        component(name, definition) {
          found[name] = definition;
          return this;
        },
      });
      chart.value = markRaw(found.TramePlotly);
      window.racetrace_charts.ready = true;
    };
    script.onerror = function () {
      console.error("racetrace: the chart library did not load from " + url);
    };
    document.head.appendChild(script);
  }

  const TYPES = {
    f8: Float64Array,
    f4: Float32Array,
    i1: Int8Array,
    u1: Uint8Array,
    u1c: Uint8ClampedArray,
    i2: Int16Array,
    u2: Uint16Array,
    i4: Int32Array,
    u4: Uint32Array,
  };

  function isSpec(value) {
    return (
      value !== null &&
      typeof value === "object" &&
      !Array.isArray(value) &&
      typeof value.dtype === "string" &&
      typeof value.bdata === "string"
    );
  }

  // a typed-array spec as plotly decodes it: one typed array, or a row of them for a 2-D shape;
  // other shapes are left to plotly
  function decodeSpec(spec) {
    const Type = TYPES[spec.dtype];
    const dims = spec.shape === undefined ? [] : String(spec.shape).split(",").map(Number);
    if (!Type || dims.length > 2) return spec;
    const text = atob(spec.bdata);
    const bytes = new Uint8Array(text.length);
    for (let i = 0; i < text.length; i++) bytes[i] = text.charCodeAt(i);
    if (dims.length < 2) return new Type(bytes.buffer);
    const [rows, columns] = dims;
    const out = [];
    for (let r = 0; r < rows; r++) {
      out.push(new Type(bytes.buffer, r * columns * Type.BYTES_PER_ELEMENT, columns));
    }
    return out;
  }

  function decoded(value) {
    if (isSpec(value)) return decodeSpec(value);
    if (Array.isArray(value)) return value.map(decoded);
    if (value !== null && typeof value === "object") {
      const out = {};
      for (const key of Object.keys(value)) out[key] = decoded(value[key]);
      return out;
    }
    return value;
  }

  const decodedFigures = new WeakMap(); // a figure's traces -> the same traces, arrays decoded

  function decodedTraces(data) {
    let out = decodedFigures.get(data);
    if (!out) {
      out = markRaw(data.map(decoded));
      decodedFigures.set(data, out);
    }
    return out;
  }

  // the figure's traces (decoded) then the overlay's: the same array while neither changes
  function traces(memo, data, overlayData) {
    if (memo.data !== data || memo.overlayData !== overlayData) {
      const extra = overlayData || [];
      const figure = decodedTraces(data || []);
      memo.data = data;
      memo.overlayData = overlayData;
      memo.traces = extra.length ? figure.concat(extra) : figure;
    }
    return memo.traces;
  }

  // the figure's layout with the overlay's shapes after its own (a new object)
  function withShapes(layout, shapes) {
    if (!shapes || !shapes.length) return layout || {};
    return { ...(layout || {}), shapes: ((layout && layout.shapes) || []).concat(shapes) };
  }

  // the same overlay traces (a change of them is a change of the figure's traces)
  function sameTraces(a, b) {
    const x = a || [];
    const y = b || [];
    return x === y || (x.length === 0 && y.length === 0);
  }

  const RacetraceChart = defineComponent({
    name: "RacetraceChart",
    inheritAttrs: false,
    setup(_props, { attrs }) {
      const memo = {};
      const shown = shallowRef(false); // this chart's turn to draw has come
      const plot = shallowRef(null); // the TramePlotly component once mounted (its $el)
      // the overlay whose marks the chart shows and the one it is to show (a frame's marks), the
      // figure's layout and overlay traces it was last drawn with, the layout given to trame-plotly
      // (the figure's with the marks it was drawn with), and the animation frame that moves the
      // marks (0: none asked)
      const marks = {
        shown: null,
        wanted: null,
        figureLayout: null,
        shownData: null,
        layout: null,
        frame: 0,
      };

      function moveMarks() {
        marks.frame = 0;
        const wanted = marks.wanted;
        // the plot's element (TramePlotly's inner div; its exposed relayout() does not reach plotly)
        const root = plot.value && plot.value.$el;
        const element = root && root.querySelector && root.querySelector(".js-plotly-plot");
        if (!wanted || wanted === marks.shown) return;
        if (!element || !element._fullLayout) {
          if (plot.value) marks.frame = requestAnimationFrame(moveMarks); // not drawn yet: later
          return;
        }
        marks.shown = wanted;
        // the shapes only: plotly supplies the shapes' defaults and draws them again, nothing else
        const layout = marks.figureLayout || {};
        window.Plotly.relayout(element, { shapes: (layout.shapes || []).concat(wanted.shapes || []) });
      }

      onUpdated(() => {
        if (marks.wanted !== marks.shown && !marks.frame) {
          marks.frame = requestAnimationFrame(moveMarks);
        }
      });
      onBeforeUnmount(() => {
        if (marks.frame) cancelAnimationFrame(marks.frame);
      });
      watch(
        chart,
        (component) => {
          if (component && !shown.value) inTurn(() => (shown.value = true));
        },
        { immediate: true },
      );
      return () => {
        if (!chart.value || !shown.value) {
          return h("div", { class: "text-caption text-medium-emphasis pa-2" }, "loading chart\u2026");
        }
        const { overlay, ...rest } = attrs;
        if (!overlay) return h(chart.value, rest);
        const data = traces(memo, rest.data, overlay.data);
        if (rest.layout !== marks.figureLayout || !sameTraces(overlay.data, marks.shownData)) {
          // a new figure: drawn whole, with the overlay's marks of now
          marks.figureLayout = rest.layout;
          marks.shownData = overlay.data;
          marks.layout = withShapes(rest.layout, overlay.shapes);
          marks.shown = overlay;
        }
        marks.wanted = overlay;
        return h(chart.value, { ...rest, ref: plot, data, layout: marks.layout });
      };
    },
  });

  window.racetrace_charts = {
    ready: false,
    load,
    install(app) {
      app.component("racetrace-chart", RacetraceChart);
    },
  };
})();
