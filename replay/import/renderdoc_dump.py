#!/usr/bin/env python3
"""Dumps what `aoreplay import renderdoc` needs from one RenderDoc capture (.rdc).

The aoreplay binary embeds this script and runs it, once per capture, with Debian's python3 and
RenderDoc's Python module (python3-renderdoc, or the one in --renderdoc-python DIR). It replays
the capture to the chosen event and writes, into --out:

  dump.json    the choices (event, resources, formats, viewport, matrices) and, on bad input, the
               error, after whatever was found before it
  depth.bin    the depth attachment's texels as RenderDoc returns them (GetTextureData)
  normals.bin  the normal target's texels, when one was asked for
  postvs.bin   the draw's triangles after the vertex shader: clip-space x, y, z, w (float32) of
               each corner, three corners a triangle, for the import's self-check

It only reads and reports: decoding the texels, checking the matrices and writing the capture
are the C++ side's job (replay/import/). Bad input is {"error": {"field", "message"}} in dump.json
and exit status 0; any other exit status means the script itself failed.
"""
import argparse
import array
import json
import os
import struct
import sys
import time

RDC_MAGIC = b"RDOC\0\0\0\0"


class ImportFailure(Exception):
    """Bad input: reported to the user with the option (field) it concerns."""

    def __init__(self, field, message):
        super().__init__(message)
        self.field = field


def parse_arguments():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("capture")
    p.add_argument("--out", required=True)
    p.add_argument("--renderdoc-python", default="")
    p.add_argument("--event", type=int)
    p.add_argument("--pass", dest="pass_name")
    p.add_argument("--depth", default="auto")
    p.add_argument("--normals", default="none")
    p.add_argument("--view")
    p.add_argument("--projection")
    p.add_argument("--view-projection", dest="view_projection")
    p.add_argument("--array-rows", action="store_true")
    p.add_argument("--sample", type=int, default=0)
    p.add_argument("--no-self-check", action="store_true")
    p.add_argument("--no-display", action="store_true")  # no X display: stop at an OpenGL capture and say so
    return p.parse_args()


def read_header(path):
    """The capture's file format version and the RenderDoc version string it was made with."""
    try:
        with open(path, "rb") as f:
            head = f.read(32)
    except OSError as e:
        raise ImportFailure("", "cannot read the file: %s" % e.strerror)
    if len(head) < 32 or head[:8] != RDC_MAGIC:
        raise ImportFailure("", "not a RenderDoc capture (the file does not start with RenderDoc's RDOC header)")
    file_version = struct.unpack_from("<I", head, 8)[0]
    made_with = head[16:32].split(b"\0")[0].decode("ascii", "replace").strip()
    return file_version, made_with


def import_renderdoc(directory):
    if directory:
        if not os.path.isfile(os.path.join(directory, "renderdoc.so")):
            raise ImportFailure("--renderdoc-python", "no RenderDoc Python module (renderdoc.so) in %s" % directory)
        sys.path.insert(0, directory)
    try:
        import renderdoc
    except ImportError as e:
        where = directory or "this Python's path (%s)" % sys.executable
        raise ImportFailure("--renderdoc-python",
                            "cannot import RenderDoc's Python module from %s: %s; install Debian's python3-renderdoc "
                            "(apt-get install python3-renderdoc) or give --renderdoc-python DIR with the renderdoc.so "
                            "of a RenderDoc build" % (where, e))
    return renderdoc


def version_tuple(text):
    parts = []
    for piece in text.split()[0].lstrip("v").split(".")[:2] if text else []:
        digits = "".join(c for c in piece if c.isdigit())
        parts.append(int(digits) if digits else 0)
    return tuple(parts)


def incompatible_codes(rd):
    return (rd.ResultCode.FileIncompatibleVersion, rd.ResultCode.APIIncompatibleVersion)


def open_capture_file(rd, path, made_with):
    cap = rd.OpenCaptureFile()
    result = cap.OpenFile(path, "", None)
    installed = rd.GetVersionString()
    if result.code in incompatible_codes(rd):
        if version_tuple(made_with) > version_tuple(installed):
            raise ImportFailure("", "made with RenderDoc %s, newer than the installed RenderDoc %s, which cannot open "
                                "it: give --renderdoc-python DIR of a RenderDoc %s (or newer) build (%s)"
                                % (made_with, installed, made_with.split()[0], result.Message()))
        raise ImportFailure("", "made with RenderDoc %s, which the installed RenderDoc %s cannot open: %s"
                            % (made_with, installed, result.Message()))
    if result.code != rd.ResultCode.Succeeded:
        raise ImportFailure("", "RenderDoc %s cannot open it: %s" % (installed, result.Message()))
    if cap.LocalReplaySupport() != rd.ReplaySupport.Supported:
        raise ImportFailure("", "RenderDoc cannot replay this %s capture on this machine" % cap.DriverName())
    return cap


def start_replay(rd, cap, made_with):
    installed = rd.GetVersionString()
    result, controller = cap.OpenCapture(rd.ReplayOptions(), None)
    if result.code in incompatible_codes(rd):
        raise ImportFailure("", "made with RenderDoc %s, which the installed RenderDoc %s cannot replay: %s"
                            % (made_with, installed, result.Message()))
    if result.code != rd.ResultCode.Succeeded:
        raise ImportFailure("", "RenderDoc %s cannot replay it: %s" % (installed, result.Message()))
    return controller


class Frame:
    """The capture's actions in order, with the marker regions each lies in."""

    def __init__(self, rd, controller):
        self.rd = rd
        self.controller = controller
        self.structured = controller.GetStructuredFile()
        self.actions = []  # (action, [marker names, outermost first])
        self._walk(controller.GetRootActions(), [])
        self.resources = {r.resourceId: r.name for r in controller.GetResources()}
        self.textures = {t.resourceId: t for t in controller.GetTextures()}

    def _walk(self, actions, markers):
        for a in actions:
            self.actions.append((a, markers))
            if a.children:
                inner = markers + [a.GetName(self.structured)] if a.flags & self.rd.ActionFlags.PushMarker else markers
                self._walk(a.children, inner)

    def draws(self):
        return [(a, m) for a, m in self.actions if a.flags & self.rd.ActionFlags.Drawcall]

    def name_of(self, resource_id):
        return self.resources.get(resource_id, str(resource_id))

    def describe(self, action):
        return "%s (%s)" % (action.eventId, action.GetName(self.structured))

    def find_texture(self, text, field):
        """A texture by RenderDoc's name for it, by 'ResourceId::N' or by N."""
        wanted = text.strip()
        for rid in self.textures:
            if self.name_of(rid) == wanted or str(rid) == wanted or str(rid) == "ResourceId::" + wanted:
                return rid
        listed = ", ".join("%s (%s, %s)" % (self.name_of(r), str(r).replace("ResourceId::", "id "), t.format.Name())
                           for r, t in self.textures.items())
        raise ImportFailure(field, "no texture %r in the capture; its textures: %s" % (text, listed))


def id_number(resource_id):
    return int(str(resource_id).split("::")[-1])


def list_draws(frame, draws):
    return ", ".join(frame.describe(a) for a, _ in draws) or "none"


def choose_event(frame, args, depth_id):
    """The event to replay to and why it was chosen."""
    null = frame.rd.ResourceId.Null()
    draws = frame.draws()
    with_depth = [(a, m) for a, m in draws if a.depthOut != null and (depth_id is None or a.depthOut == depth_id)]
    if args.event is not None:
        for a, m in frame.actions:
            if a.eventId == args.event:
                return a, m, "--event"
        raise ImportFailure("--event", "event %d is not an action of the capture; its draws with a depth target: %s"
                            % (args.event, list_draws(frame, with_depth)))
    if args.pass_name is not None:
        markers = sorted({name for _, m in frame.actions for name in m})
        in_pass = [(a, m) for a, m in with_depth if args.pass_name in m]
        if not in_pass:
            raise ImportFailure("--pass", "no draw with a depth target in a pass (marker region) named %r; the "
                                "capture's passes: %s" % (args.pass_name, ", ".join(markers) or "none"))
        a, m = in_pass[-1]
        return a, m, "last draw with a depth target in pass %s" % args.pass_name
    if not with_depth:
        what = "the depth target %s" % frame.name_of(depth_id) if depth_id is not None else "a depth target"
        raise ImportFailure("--event", "no draw in the capture writes %s; its draws: %s"
                            % (what, list_draws(frame, draws)))
    return scene_draw(frame, with_depth)


MAX_DEFAULT_EVENT_PROBES = 256  # draws looked at from the end for one that writes depth


def writes_depth(frame):
    """Whether the current event's draw tests and writes depth (a scene draw, not a composite)."""
    state = frame.controller.GetPipelineState()
    if state.IsCaptureVK():
        ds = frame.controller.GetVulkanPipelineState().depthStencil
        return bool(ds.depthTestEnable and ds.depthWriteEnable)
    if state.IsCaptureGL():
        ds = frame.controller.GetGLPipelineState().depthState
        return bool(ds.depthEnable and ds.depthWrites)
    return True


def scene_draw(frame, with_depth):
    """The last draw with a depth target that also tests and writes depth: full-screen copies and
    post-processing after the scene (depth test or writes off) are passed over."""
    skipped = 0
    for a, m in reversed(with_depth[-MAX_DEFAULT_EVENT_PROBES:]):
        frame.controller.SetFrameEvent(a.eventId, False)
        if writes_depth(frame):
            if not skipped:
                return a, m, "last draw with a depth target"
            return a, m, ("last draw that tests and writes depth (%d later draw%s with depth test or writes off "
                          "passed over)" % (skipped, "" if skipped == 1 else "s"))
        skipped += 1
    a, m = with_depth[-1]
    return a, m, "last draw with a depth target (none of the last %d tests and writes depth)" % skipped


def texture_dump(frame, rid, mip, layer, sample, path, field):
    """One subresource's texels; of a multisampled texture, sample `sample` (RenderDoc returns each)."""
    rd = frame.rd
    tex = frame.textures[rid]
    if sample >= max(1, tex.msSamp):
        if tex.msSamp > 1:
            raise ImportFailure("--sample", "%s has %d samples: --sample is 0 to %d, not %d"
                                % (frame.name_of(rid), tex.msSamp, tex.msSamp - 1, sample))
        raise ImportFailure("--sample", "%s is not multisampled: --sample %d has no sample to pick"
                            % (frame.name_of(rid), sample))
    data = frame.controller.GetTextureData(rid, rd.Subresource(mip, layer, sample))
    with open(path, "wb") as f:
        f.write(bytes(data))
    fmt = tex.format
    return {
        "resource": frame.name_of(rid), "id": id_number(rid), "file": os.path.basename(path),
        "width": max(1, tex.width >> mip), "height": max(1, tex.height >> mip), "mip": mip, "layer": layer,
        "samples": max(1, tex.msSamp), "sample": sample, "bytes": len(data),
        "format": {"name": fmt.Name(), "components": fmt.compCount, "component_bytes": fmt.compByteWidth,
                   "bgra": bool(fmt.BGRAOrder())},
    }


def dump_depth(frame, args, out_dir):
    bound = frame.controller.GetPipelineState().GetDepthTarget()
    if bound.resourceId == frame.rd.ResourceId.Null():
        raise ImportFailure("--event", "no depth target at event %s; the capture's draws with a depth target: %s"
                            % (frame.current, list_draws(frame, [(a, m) for a, m in frame.draws()
                                                                  if a.depthOut != frame.rd.ResourceId.Null()])))
    return texture_dump(frame, bound.resourceId, bound.firstMip, bound.firstSlice, args.sample,
                        os.path.join(out_dir, "depth.bin"), "--depth")


def dump_normals(frame, args, out_dir):
    if args.normals == "none":
        return None
    rid = frame.find_texture(args.normals, "--normals")
    mip, layer = 0, 0
    for bound in frame.controller.GetPipelineState().GetOutputTargets():
        if bound.resourceId == rid:
            mip, layer = bound.firstMip, bound.firstSlice
    sample = args.sample if frame.textures[rid].msSamp > 1 else 0  # the depth's sample, where the normals have samples
    return texture_dump(frame, rid, mip, layer, sample, os.path.join(out_dir, "normals.bin"), "--normals")


SHADER_STAGES = ("Vertex", "Hull", "Domain", "Geometry", "Pixel")


def stage_name(stage):
    return {"Vertex": "vertex", "Hull": "tessellation control", "Domain": "tessellation evaluation",
            "Geometry": "geometry", "Pixel": "fragment"}[stage]


def type_text(var_type):
    return var_type.name + ("[%d]" % var_type.elements if var_type.elements > 1 else "")


def var_type_name(rd, value):
    """A VarType by its name (the Python module gives some enums as plain integers)."""
    name = getattr(value, "name", None)
    if isinstance(name, str):
        return name
    for candidate in dir(rd.VarType):
        if not candidate.startswith("_") and getattr(rd.VarType, candidate) == value:
            return candidate
    return "type %s" % value


def variable_text(rd, variable):
    """What a variable read from a block is, in words: '4 x 4 Float', 'an array of 7 (1 x 4 Float)'."""
    if variable.members:
        first = variable.members[0]
        if first.name.endswith("]"):
            return "an array of %d (%s)" % (len(variable.members), variable_text(rd, first))
        return "a struct of %d members" % len(variable.members)
    return "%d x %d %s" % (variable.rows, variable.columns, var_type_name(rd, variable.type))


def split_index(piece):
    """'child[4]' -> ('child', 4); 'view' -> ('view', None)."""
    if piece.endswith("]") and "[" in piece:
        name, index = piece[:-1].split("[", 1)
        if name and index.isdigit():
            return name, int(index)
        raise ImportFailure(None, "%r: an element is NAME[I] with I a whole number" % piece)
    return piece, None


def matrix_from_elements(rd, variable, first, as_rows, spec, field):
    """Four consecutive vec4 elements of an array member, from `first`, as the matrix's columns or rows."""
    elements = variable.members
    if not elements or not elements[0].name.endswith("]"):
        raise ImportFailure(field, "%s is %s, not an array of vec4: [I] picks four elements of an array"
                            % (spec, variable_text(rd, variable)))
    if first + 4 > len(elements):
        raise ImportFailure(field, "%s: elements %d..%d are past the end of the array (%d elements)"
                            % (spec, first, first + 3, len(elements)))
    picked = elements[first:first + 4]
    for element in picked:
        if element.members or element.rows * element.columns != 4 or element.type != rd.VarType.Float:
            raise ImportFailure(field, "%s: element %s is %s, not a float vec4" % (spec, element.name, variable_text(rd, element)))
    values = [[float(x) for x in e.value.f32v[:4]] for e in picked]
    return [values[r][c] if as_rows else values[c][r] for r in range(4) for c in range(4)]


def find_member(variables, path):
    """The reflected variable and its contents at a '.'-separated path inside a block."""
    found = None
    for piece in path:
        matches = [v for v in variables if v.name == piece]
        if not matches:
            return None
        found = matches[0]
        variables = found.members
    return found


def read_matrix(frame, spec, field, array_rows):
    """The 4x4 matrix BLOCK.member (or the four vec4 elements BLOCK.member[I]) of the event's shaders,
    in a uniform or push-constant block: values row by row, as RenderDoc gives them."""
    rd = frame.rd
    pieces = spec.split(".")
    if len(pieces) < 2 or not all(pieces):
        raise ImportFailure(field, "%r is not BLOCK.member or BLOCK.member[I] (the block's instance name, a dot, the "
                            "member)" % spec)
    block_name, member_path = pieces[0], pieces[1:]
    try:
        last, first = split_index(member_path[-1])
    except ImportFailure as e:
        raise ImportFailure(field, str(e))
    member_path = member_path[:-1] + [last]
    state = frame.controller.GetPipelineState()
    for stage_key in SHADER_STAGES:
        stage = getattr(rd.ShaderStage, stage_key)
        reflection = state.GetShaderReflection(stage)
        if reflection is None:
            continue
        for storage in list(reflection.readWriteResources) + list(reflection.readOnlyResources):
            if storage.name == block_name and not storage.isTexture:
                raise ImportFailure(field, "%s is a storage buffer of the %s shader: matrices in storage buffers are "
                                    "not supported yet (only uniform and push-constant blocks)"
                                    % (block_name, stage_name(stage_key)))
        for index, block in enumerate(reflection.constantBlocks):
            members = ", ".join("%s (%s)" % (v.name, type_text(v.type)) for v in block.variables)
            if block.name != block_name:
                continue
            if block.bufferBacked:
                bound = state.GetConstantBuffer(stage, index, 0)
                buffer_id, offset, size = bound.resourceId, bound.byteOffset, bound.byteSize
            else:  # push constants (GL: default-block uniforms, $Globals): RenderDoc reads them from the state
                buffer_id, offset, size = rd.ResourceId.Null(), 0, 0
            contents = frame.controller.GetCBufferVariableContents(
                state.GetGraphicsPipelineObject(), reflection.resourceId, stage, state.GetShaderEntryPoint(stage),
                index, buffer_id, offset, size)
            variable = find_member(contents, member_path)
            kind = "uniform block" if block.bufferBacked else unbacked_kind(frame)
            if variable is None:
                raise ImportFailure(field, "%s %s (%s shader) has no member %s; its members: %s"
                                    % (kind, block_name, stage_name(stage_key), ".".join(member_path), members))
            found = {"block": block_name, "member": ".".join(pieces[1:]), "stage": stage_name(stage_key),
                     "push_constant": not block.bufferBacked,
                     "buffer": frame.name_of(buffer_id) if block.bufferBacked else unbacked_kind(frame)}
            if first is not None:
                found["rows"] = matrix_from_elements(rd, variable, first, array_rows, spec, field)
                found["declared_row_major"] = False
                found["array_read_as"] = "rows" if array_rows else "columns"
                return found
            if variable.members or variable.rows != 4 or variable.columns != 4 or variable.type != rd.VarType.Float:
                hint = " (BLOCK.member[I] reads four of its vec4 elements)" if variable.members else ""
                raise ImportFailure(field, "%s is %s, not a 4 x 4 float matrix%s" % (spec, variable_text(rd, variable), hint))
            found["declared_row_major"] = bool(variable.RowMajor())
            found["rows"] = [float(x) for x in variable.value.f32v[:16]]
            return found
    raise ImportFailure(field, "no uniform block or %s named %s in the shaders at event %s; the blocks there: %s"
                        % (unbacked_kind(frame), block_name, frame.current, block_listing(frame)))


def viewport_of(state):
    v = state.GetViewport(0)
    return {"x": v.x, "y": v.y, "width": v.width, "height": v.height, "min_depth": v.minDepth,
            "max_depth": v.maxDepth}


def unbacked_kind(frame):
    """What a block without a buffer is in this API: Vulkan's push constants, GL's default-block
    uniforms (RenderDoc names that block $Globals)."""
    return "default-block uniforms" if frame.controller.GetPipelineState().IsCaptureGL() else "push constants"


def block_listing(frame):
    """The uniform and push-constant blocks of the event's shaders, for messages."""
    rd = frame.rd
    state = frame.controller.GetPipelineState()
    listed = []
    for stage_key in SHADER_STAGES:
        reflection = state.GetShaderReflection(getattr(rd.ShaderStage, stage_key))
        for block in (reflection.constantBlocks if reflection else []):
            members = ", ".join("%s (%s)" % (v.name, type_text(v.type)) for v in block.variables)
            listed.append("%s [%s shader%s: %s]" % (block.name, stage_name(stage_key),
                                                    "" if block.bufferBacked else ", " + unbacked_kind(frame),
                                                    members))
    return "; ".join(listed) or "none"


def conventions_of(rd, controller, api):
    """How this API maps clip space to the depth target: read from the captured state, never assumed."""
    state = controller.GetPipelineState()
    viewport = state.GetViewport(0)
    c = {"api": api, "depth_range": [viewport.minDepth, viewport.maxDepth]}
    if state.IsCaptureVK():
        c.update({"clip_z": "-1..1" if controller.GetVulkanPipelineState().viewportScissor.depthNegativeOneToOne
                  else "0..1", "clip_y_at_row_0": "-1", "rows": "top-down"})
    elif state.IsCaptureGL():
        gl = controller.GetGLPipelineState()
        processing = gl.vertexProcessing
        c.update({"clip_z": "-1..1" if processing.clipNegativeOneToOne else "0..1",
                  "clip_y_at_row_0": "-1" if processing.clipOriginLowerLeft else "+1", "rows": "bottom-up",
                  "depth_range": [gl.rasterizer.viewports[0].minDepth, gl.rasterizer.viewports[0].maxDepth]})
    return c


MAX_CHECK_TRIANGLES = 65536  # beyond this many, every k-th triangle (the check's cost stays bounded)
TRIANGLE_TOPOLOGIES = ("TriangleList", "TriangleStrip", "TriangleFan")


def check_impossible(reason):
    return {"possible": False, "reason": reason}


def corner_indices(rd, mesh, controller):
    """The post-VS vertex index of each drawn corner, in order, with primitive restart kept as None."""
    if mesh.indexResourceId == rd.ResourceId.Null():
        return list(range(mesh.numIndices))
    kind = {1: "B", 2: "H", 4: "I"}[mesh.indexByteStride]
    data = controller.GetBufferData(mesh.indexResourceId, mesh.indexByteOffset, mesh.numIndices * mesh.indexByteStride)
    indices = array.array(kind)
    indices.frombytes(bytes(data)[:mesh.numIndices * mesh.indexByteStride])
    restart = mesh.restartIndex if mesh.allowRestart else None
    return [None if i == restart else i + mesh.baseVertex for i in indices]


def triangles_of(topology, corners):
    """Corner index triples of a list, strip or fan (restarts split strips and fans)."""
    if topology == "TriangleList":
        return [tuple(corners[i:i + 3]) for i in range(0, len(corners) - 2, 3) if None not in corners[i:i + 3]]
    out, run = [], []
    for c in corners + [None]:
        if c is not None:
            run.append(c)
            continue
        for i in range(len(run) - 2):
            if topology == "TriangleFan":
                out.append((run[0], run[i + 1], run[i + 2]))
            else:
                out.append((run[i], run[i + 1], run[i + 2]) if i % 2 == 0 else (run[i + 1], run[i], run[i + 2]))
        run = []
    return out


def positions_of(controller, mesh, vertices):
    """The first `vertices` post-VS vertices' first output, the position (clip x, y, z, w), as a
    flat float list. Only their bytes are read: RenderDoc keeps every instance in one buffer, and
    reading to its end for each of 1024 instances took 136 s (Qt's hellogles3)."""
    data = bytes(controller.GetBufferData(mesh.vertexResourceId, mesh.vertexByteOffset, vertices * mesh.vertexByteStride))
    floats = array.array("f")
    floats.frombytes(data[:len(data) // 4 * 4])
    stride = mesh.vertexByteStride // 4
    return floats, stride


def dump_post_vs(frame, action, out_dir):
    """The draw's triangles in clip space, for the self-check, or why the check cannot run."""
    rd, controller = frame.rd, frame.controller
    state = controller.GetPipelineState()
    for stage, what in (("Geometry", "a geometry shader"), ("Hull", "tessellation"), ("Domain", "tessellation")):
        if state.GetShaderReflection(getattr(rd.ShaderStage, stage)) is not None:
            return check_impossible("the draw uses %s, so the vertex shader's output is not what was rasterised" % what)
    if not action.flags & rd.ActionFlags.Drawcall:
        return check_impossible("event %s is not a draw" % frame.current)
    if state.MultiviewBroadcastCount() > 1:
        return check_impossible("the draw is multiview (%d views)" % state.MultiviewBroadcastCount())
    out = array.array("f")
    instances = max(1, action.numInstances)
    triangles_seen = 0
    topology = ""
    for instance in range(instances):
        mesh = controller.GetPostVSData(instance, 0, rd.MeshDataStage.VSOut)
        if mesh.vertexResourceId == rd.ResourceId.Null() or mesh.numIndices == 0:
            why = mesh.status or "RenderDoc returned no post-vertex-shader data"
            return check_impossible("no post-vertex-shader data for instance %d: %s" % (instance, why))
        names = {getattr(rd.Topology, name): name for name in dir(rd.Topology) if not name.startswith("_")}
        topology = names.get(mesh.topology, str(mesh.topology))
        if topology not in TRIANGLE_TOPOLOGIES:
            return check_impossible("the draw's topology is %s, not triangles" % topology)
        if mesh.vertexByteStride < 16:
            return check_impossible("post-vertex-shader records of %d bytes hold no position" % mesh.vertexByteStride)
        corners = corner_indices(rd, mesh, controller)
        positions, stride = positions_of(controller, mesh, 1 + max((c for c in corners if c is not None), default=-1))
        triangles = triangles_of(topology, corners)
        step = max(1, len(triangles) * instances // MAX_CHECK_TRIANGLES)
        for t in triangles[::step]:
            for v in t:
                if (v + 1) * stride > len(positions):
                    return check_impossible("post-vertex-shader index %d is past the %d vertices RenderDoc returned"
                                            % (v, len(positions) // stride))
                out.extend(positions[v * stride:v * stride + 4])
        triangles_seen += len(triangles)
    with open(os.path.join(out_dir, "postvs.bin"), "wb") as f:
        f.write(out.tobytes())
    return {"possible": True, "file": "postvs.bin", "topology": topology, "instances": instances,
            "triangles": triangles_seen, "triangles_dumped": len(out) // 12}


def dump(args, result):
    """Fills `result` step by step, so that what was found before an error is still reported."""
    file_version, made_with = read_header(args.capture)
    result.update({"made_with": made_with, "file_version": file_version})
    rd = import_renderdoc(args.renderdoc_python)
    result["renderdoc"] = rd.GetVersionString()
    rd.InitialiseReplay(rd.GlobalEnvironment(), [])
    cap = open_capture_file(rd, args.capture, made_with)
    result["api"] = cap.DriverName()
    if args.no_display and result["api"].startswith("OpenGL"):
        result["needs_display"] = True  # desktop GL replays through GLX: aoreplay starts an X server
        cap.Shutdown()
        return
    controller = start_replay(rd, cap, made_with)
    try:
        frame = Frame(rd, controller)
        depth_id = None if args.depth == "auto" else frame.find_texture(args.depth, "--depth")
        action, markers, why = choose_event(frame, args, depth_id)
        frame.current = frame.describe(action)
        controller.SetFrameEvent(action.eventId, True)
        result["event"] = {"id": action.eventId, "name": action.GetName(frame.structured), "passes": markers,
                           "why": why}
        result["viewport"] = viewport_of(controller.GetPipelineState())
        result["conventions"] = conventions_of(rd, controller, result["api"])
        result["blocks"] = block_listing(frame)
        result["depth"] = dump_depth(frame, args, args.out)
        if depth_id is not None and result["depth"]["id"] != id_number(depth_id):
            raise ImportFailure("--depth", "at event %s the depth target is %s, not %s"
                                % (frame.current, result["depth"]["resource"], args.depth))
        result["normals"] = dump_normals(frame, args, args.out)
        if args.view_projection:
            result["view_projection"] = read_matrix(frame, args.view_projection, "--view-projection", args.array_rows)
        else:
            result["view"] = read_matrix(frame, args.view, "--view", args.array_rows)
            result["projection"] = read_matrix(frame, args.projection, "--projection", args.array_rows)
        started = time.monotonic()
        result["self_check"] = check_impossible("--no-self-check") if args.no_self_check else \
            dump_post_vs(frame, action, args.out)
        result["self_check"]["seconds"] = time.monotonic() - started
    finally:
        controller.Shutdown()
        cap.Shutdown()


def main():
    args = parse_arguments()
    result = {}
    try:
        dump(args, result)
    except ImportFailure as e:
        result["error"] = {"field": e.field, "message": str(e)}
    with open(os.path.join(args.out, "dump.json"), "w") as f:
        json.dump(result, f, indent=1)
    # After a capture it could not open, RenderDoc 1.24 sometimes keeps an ordinary interpreter exit
    # waiting forever (3 runs in 30 on a truncated .rdc here; none in 40 with this exit). All is
    # written, so leave without the interpreter's teardown.
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(0)


if __name__ == "__main__":
    main()
