// SPDX-License-Identifier: GPL-3.0-or-later
//
// Flamenco job type "prism-render": renders frames with Prism, Blender's spectral path tracer
// add-on, with every frame's samples split into chunks that separate workers render at once.
//
//   frame F, chunk k of K  →  render task: samples k·N … k·N+N−1 (N = samples / K) of frame F into
//                             a chunk EXR
//   frame F                →  merge task, after its K chunks: one EXR (or PNG), the image one render
//                             of all the samples writes on one machine, bit for bit
//   chunks = 1             →  one plain render task per frame, no merge
//
// Progress: render.py prints Blender's "Time: …" line after every pass, which Flamenco's worker
// counts as a step; a render task has as many steps as passes (samples / samples_per_pass).
//
// Install: copy this file into the `scripts/` folder next to the flamenco-manager executable and
// restart the Manager. Workers need Blender with Prism installed, and the Manager variable
// `prism` (or the `render_script` setting) pointing at Prism's render.py on each platform.
// See docs/farm.md in the Prism repository.

const DEFAULT_RENDER_SCRIPT = "{prism}/render.py";
const TASK_TYPE = "blender";

const JOB_TYPE = {
    label: "Prism Render",
    description: "Render with Prism, each frame's samples split into chunks over several workers and merged",
    settings: [
        {
            key: "blendfile",
            type: "string",
            subtype: "file_path",
            required: true,
            visible: "web",
            description: "The .blend file to render, on shared storage as the workers see it",
        },
        {
            key: "frames",
            type: "string",
            required: true,
            eval: "f'{C.scene.frame_start}..{C.scene.frame_end}'",
            evalInfo: { showLinkButton: true, description: "The scene's frame range" },
            description: "Frames to render, e.g. '1..24', '7' or '1-10, 15'",
        },
        {
            key: "samples",
            type: "int32",
            required: true,
            default: 64,
            eval: "C.scene.prism.samples",
            propargs: { min: 1 },
            description: "Samples per pixel of every finished frame (all of its chunks together)",
        },
        {
            key: "chunks",
            type: "int32",
            required: true,
            default: 1,
            propargs: { min: 1, max: 1024 },
            description:
                "Sample chunks per frame, each its own task on any worker; samples must be a multiple of it. " +
                "1 renders plain frames without a merge",
        },
        {
            key: "samples_per_pass",
            type: "int32",
            default: 1,
            eval: "C.scene.prism.samples_per_pass",
            propargs: { min: 1 },
            description:
                "The scene's Samples per Pass: each pass is one step of a task's progress. Chunks merge bit " +
                "for bit into one render's image when their samples are a multiple of it",
        },
        {
            key: "seed",
            type: "int32",
            default: 0,
            eval: "C.scene.prism.seed",
            propargs: { min: 0 },
            description: "Random seed: the same seed renders the same image",
        },
        {
            key: "render_output_path",
            type: "string",
            subtype: "file_path",
            required: true,
            description:
                "Absolute path of the finished frames on shared storage, .exr (scene-linear) or .png (the " +
                "scene's view transform); the last run of # becomes the frame number, e.g. /render/shot/prism_####.exr",
        },
        {
            key: "render_script",
            type: "string",
            subtype: "file_path",
            default: DEFAULT_RENDER_SCRIPT,
            description:
                "Prism's render.py as the workers see it; {prism} is a Manager variable holding the folder " +
                "Prism is installed in on each platform",
        },
    ],
};

function compileJob(job) {
    const request = readSettings(job.settings);
    const chunkRoot = path.join(path.dirname(request.outputTemplate), "prism-chunks", job.jobID);
    print("Prism job", job.name, ":", request.frames.length, "frames x", request.chunks, "chunks,",
          request.samplesPerChunk, "samples each");

    for (const frame of request.frames) {
        const finalPath = framePath(request.outputTemplate, frame);
        if (request.chunks === 1) {
            job.addTask(plainFrameTask(request, frame));
            continue;
        }
        const chunkTasks = [];
        const chunkPaths = [];
        for (let chunk = 0; chunk < request.chunks; chunk++) {
            // render.py puts the frame number in place of the #: frame_0001_chunk_0000.exr
            const chunkTemplate = path.join(chunkRoot, "frame_####_chunk_" + zeroPadded(chunk, 4) + ".exr");
            const task = chunkTask(request, frame, chunk, chunkTemplate);
            job.addTask(task);
            chunkTasks.push(task);
            chunkPaths.push(framePath(chunkTemplate, frame));
        }
        const merge = mergeTask(request, frame, chunkPaths, finalPath);
        for (const task of chunkTasks) {
            merge.addDependency(task);
        }
        job.addTask(merge);
    }
}

// The job's settings, checked, with the frame list and samples per chunk worked out.
// Throws an Error naming the setting and the fix; Flamenco shows it to whoever submitted the job.
function readSettings(settings) {
    const samples = wholeNumber(settings, "samples", 1);
    const chunks = wholeNumber(settings, "chunks", 1);
    const samplesPerPass = settings.samples_per_pass === undefined ? 1 : wholeNumber(settings, "samples_per_pass", 1);
    const seed = settings.seed === undefined ? 0 : wholeNumber(settings, "seed", 0);
    if (samples % chunks !== 0) {
        const lower = samples - (samples % chunks);
        throw new Error(
            `Prism Render: samples (${samples}) is not a multiple of chunks (${chunks}); every chunk renders ` +
            `the same number of samples. Use ${lower > 0 ? lower + " or " : ""}${lower + chunks} samples, ` +
            `or a number of chunks that divides ${samples}.`);
    }
    const output = requiredText(settings, "render_output_path");
    const extension = output.slice(output.lastIndexOf(".")).toLowerCase();
    if (extension !== ".exr" && extension !== ".png") {
        throw new Error(`Prism Render: render_output_path '${output}' must end in .exr or .png.`);
    }
    if (!isAbsolute(output)) {
        throw new Error(
            `Prism Render: render_output_path '${output}' is not an absolute path; give the full path on ` +
            `shared storage (a Blender '//' path is relative to the .blend file, which the workers do not know).`);
    }
    return {
        blendfile: requiredText(settings, "blendfile"),
        frames: frameList(requiredText(settings, "frames")),
        samples: samples,
        chunks: chunks,
        samplesPerChunk: samples / chunks,
        samplesPerPass: samplesPerPass,
        seed: seed,
        outputTemplate: withFrameNumber(output),
        renderScript: settings.render_script ? String(settings.render_script) : DEFAULT_RENDER_SCRIPT,
    };
}

function wholeNumber(settings, key, minimum) {
    const value = settings[key];
    if (typeof value !== "number" || !Number.isInteger(value) || value < minimum) {
        throw new Error(`Prism Render: setting '${key}' must be a whole number of at least ${minimum} (got ${value}).`);
    }
    return value;
}

function requiredText(settings, key) {
    const value = settings[key];
    if (typeof value !== "string" || value.trim() === "") {
        throw new Error(`Prism Render: setting '${key}' is missing; give it in the job's settings.`);
    }
    return value.trim();
}

function frameList(frames) {
    let single;
    try {
        single = frameChunker(frames, 1);
    } catch (error) {
        throw new Error(`Prism Render: frames '${frames}' is not a frame range like '1..24', '7' or '1-10, 15' (${error}).`);
    }
    return single.map((frame) => parseInt(frame, 10));
}

// Absolute on the workers: a POSIX or Windows drive path, or one starting with a Manager variable.
function isAbsolute(filepath) {
    return filepath.startsWith("/") && !filepath.startsWith("//")
        || /^[A-Za-z]:[\\/]/.test(filepath)
        || filepath.startsWith("{");
}

// render.py's naming: a path without # gets _#### before its extension.
function withFrameNumber(output) {
    const name = path.basename(output);
    if (name.indexOf("#") >= 0) {
        return output;
    }
    const dot = name.lastIndexOf(".");
    return path.join(path.dirname(output), name.slice(0, dot) + "_####" + name.slice(dot));
}

// The last run of # in the file name becomes the zero-padded frame number (as render.py does).
function framePath(template, frame) {
    const name = path.basename(template);
    const match = /#+(?!.*#)/.exec(name);
    const numbered = name.slice(0, match.index) + zeroPadded(frame, match[0].length) +
                     name.slice(match.index + match[0].length);
    return path.join(path.dirname(template), numbered);
}

// Python's f"{number:0{width}d}": the sign counts towards the width.
function zeroPadded(number, width) {
    const sign = number < 0 ? "-" : "";
    return sign + String(Math.abs(number)).padStart(Math.max(width - sign.length, 0), "0");
}

// Blender's own arguments before Prism's: stop with exit status 1 if the script raises, instead of
// going on (Blender's default).
function blenderArguments(request) {
    return ["--python-exit-code", "1", "--python", request.renderScript, "--"];
}

// steps: the "Time: …" lines the command prints (one per pass); 0 = one step when it finishes.
function blenderCommand(blendfile, args, steps) {
    return author.Command("blender-render", {
        exe: "{blender}",
        exeArgs: "{blenderArgs}",
        argsBefore: [],
        blendfile: blendfile,
        args: args,
    }, steps || 0);
}

// Passes of a render of `samples` samples: render.py's progress steps.
function passes(request, samples) {
    return Math.ceil(samples / request.samplesPerPass);
}

function plainFrameTask(request, frame) {
    const task = author.Task(`render frame ${frame}`, TASK_TYPE);
    task.addCommand(blenderCommand(request.blendfile, blenderArguments(request).concat([
        "--frames", String(frame),
        "--samples", String(request.samples),
        "--seed", String(request.seed),
        "--output", request.outputTemplate,
    ]), passes(request, request.samples)));
    return task;
}

function chunkTask(request, frame, chunk, chunkTemplate) {
    const task = author.Task(`render frame ${frame} chunk ${chunk + 1}/${request.chunks}`, TASK_TYPE);
    task.addCommand(blenderCommand(request.blendfile, blenderArguments(request).concat([
        "--frames", String(frame),
        "--chunk-seed", String(chunk),
        "--samples", String(request.samplesPerChunk),
        "--seed", String(request.seed),
        "--output", chunkTemplate,
    ]), passes(request, request.samplesPerChunk)));
    return task;
}

// No .blend file: the merge reads the chunk EXRs (they carry what a PNG needs), and refuses a missing,
// mismatched or left-out chunk (--expect-samples) rather than write an incomplete frame.
function mergeTask(request, frame, chunkPaths, finalPath) {
    const task = author.Task(`merge frame ${frame}`, TASK_TYPE);
    task.addCommand(blenderCommand("", blenderArguments(request).concat(
        ["--merge"], chunkPaths, ["--expect-samples", String(request.samples), "--output", finalPath])));
    return task;
}
