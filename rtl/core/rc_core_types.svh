// The records that cross the module boundaries of rc_core (docs/architecture.md, "The core"),
// and the few functions that every unit applies to them in the same way. tb/gen_constants.py
// copies this text into the package rc_pkg, after the constants of docs/spec.toml it uses.
//
// Contract: types and pure functions only; no state. Widths come from the package: the core's
// number format is docs/spec.toml [fp24] (CoreFpW bits), thread numbers are CoreThrBits wide
// (enough for [core] max_threads; a core with fewer threads leaves the upper bits zero), stack
// depths CoreSpBits (0 .. [kdtree] stack_depth). Written for both Verilator and Yosys 0.23:
// packed structs, no enums (a vector cannot be cast to one in Yosys 0.23, so codes are
// localparams), no struct literals, no `$bits` of a type, no casts to a type.

localparam int unsigned CoreFpW     = 1 + Fp24ExpW + Fp24FracW;
localparam logic [CoreFpW-1:0] CoreFpPosInf = {1'b0, {Fp24ExpW{1'b1}}, {Fp24FracW{1'b0}}};  // +inf
localparam int unsigned CoreThrBits = $clog2(CoreMaxThreads);
localparam int unsigned CoreSpBits  = $clog2(KdtreeStackDepth + 1);

// What visiting a node means for its packet, decided from its record where the record is read
// (its parent's children read, or the configuration for the root): the checks of
// docs/architecture.md, "Errors".
localparam logic [1:0] NodeOk        = 2'd0;
localparam logic [1:0] NodeMalformed = 2'd1;  // an inner node: children not after it, outside the
                                              // node section, or a split that is NaN, infinite
                                              // or wider than the format
localparam logic [1:0] NodeBadList   = 2'd2;  // a leaf whose list range leaves the list section

// A node's record (docs/memory-format.md, "kd nodes") with the outcome of its checks.
typedef struct packed {
  logic [63:0] rec;
  logic [1:0]  chk;  // Node*
} node_t;

// A walk entry: a node and the rays that visit it with their intervals. It is a packet's
// current entry and what its stack holds.
typedef struct packed {
  node_t                   node;
  logic [3:0]              mask;  // active rays
  logic [3:0][CoreFpW-1:0] tmin;  // ray r at [r]
  logic [3:0][CoreFpW-1:0] tmax;
} walk_entry_t;

// A thread's current entry on its way to the traversal unit's issue: the thread and its stack
// depth come with it.
typedef struct packed {
  logic [CoreThrBits-1:0] thr;
  logic [CoreSpBits-1:0]  sp;
  walk_entry_t            entry;
} walk_item_t;

// A leaf visit for the list unit.
typedef struct packed {
  logic [CoreThrBits-1:0] thr;
  logic [3:0]             mask;   // the rays that test its triangles
  logic [29:0]            first;  // its first list entry
  logic [31:0]            count;  // its triangles (> 0)
} leaf_item_t;

// What the traversal sub-units carry beside each ray's interval, from the node's children read to
// the traversal decision (the tag of sub-unit 0).
typedef struct packed {
  logic [CoreThrBits-1:0] thr;
  logic [3:0]             mask;   // active rays
  logic [3:0]             same;   // ray r's direction sign on the split axis is the lead ray's
  logic                   lsign;  // the lead ray's sign (its near child is the right one if 1)
  logic [CoreSpBits-1:0]  sp;     // stack depth
  node_t                  kid_l;  // the left child (index left) ...
  node_t                  kid_r;  // ... and the right child (left + 1), checked
} trav_com_t;

// One ray-triangle test's result, from the intersection unit to the best-hit write-back.
typedef struct packed {
  logic [CoreThrBits-1:0] thr;
  logic [1:0]             ray;
  logic                   last;   // the test of its list entry's last ray
  logic [31:0]            tri_idx;
  logic                   hit;    // accepted against the best hit it was given
  logic [CoreFpW-1:0]     t;
  logic [CoreFpW-1:0]     u;
  logic [CoreFpW-1:0]     v;
  logic [CoreFpW-1:0]     dz;
} isect_res_t;

// A new best hit of a ray, written to every copy of the best hits at once.
typedef struct packed {
  logic [CoreThrBits-1:0] thr;
  logic [1:0]             ray;
  logic [31:0]            tri_idx;
  logic [CoreFpW-1:0]     t;
  logic [CoreFpW-1:0]     u;
  logic [CoreFpW-1:0]     v;
  logic [CoreFpW-1:0]     dz;
} hit_commit_t;

// Where a walk entry goes next (walk_route).
localparam logic [1:0] RouteTrav = 2'd0;  // an inner node: the traversal unit
localparam logic [1:0] RouteLeaf = 2'd1;  // a leaf with triangles: the list unit
localparam logic [1:0] RoutePop  = 2'd2;  // no active ray, an empty leaf or an error: the pop unit

// The checks of a node's record read at index own (Node*) (docs/architecture.md, "Errors"): an
// inner node must have its children after itself and inside the node section and a finite split
// of the format's width; a leaf's list range must lie inside the list section. In two parts, so
// a caller may register between them: node_sums, the sums and flags of the record alone, and
// node_decide, their compares with own and the section sizes. The sums travel as a vector
// {leaf, bad_split, index[29:0], list_end[32:0], next[32:0]} (Yosys 0.23 reads no functions
// of struct type): leaf, a leaf (else an inner node); bad_split, an inner node's split wider
// than the format or not finite; index, the child or list index; list_end, index + the leaf's
// triangle count; next, index + 1.
localparam int unsigned NodeSumsW = 2 + 30 + 33 + 33;

function automatic logic [NodeSumsW-1:0] node_sums(input logic [63:0] rec);
  logic [29:0] index;
  logic [31:0] upper;
  index     = rec[KdNodeIndexLsb +: 30];
  upper     = rec[KdNodeValueLsb +: 32];
  node_sums = {rec[KdNodeKindLsb +: 2] == 2'(KdNodeKindLeaf),
               ((upper >> CoreFpW) != 32'd0) || (&upper[CoreFpW-2 -: Fp24ExpW]), index,
               {3'd0, index} + {1'b0, upper}, {3'd0, index} + 33'd1};
endfunction

function automatic logic [1:0] node_decide(input logic [NodeSumsW-1:0] sums,
                                          input logic [29:0] own,
                                          input logic [31:0] node_count,
                                          input logic [31:0] list_count);
  logic        leaf, bad_split;
  logic [29:0] index;
  logic [32:0] list_end, next;
  {leaf, bad_split, index, list_end, next} = sums;
  if (leaf) begin
    node_decide = (list_end > {1'b0, list_count}) ? NodeBadList : NodeOk;
  end else begin
    node_decide = (bad_split || index <= own || next >= {1'b0, node_count}) ? NodeMalformed :
                                                                              NodeOk;
  end
endfunction

function automatic logic [1:0] node_check(input logic [63:0] rec, input logic [29:0] own,
                                         input logic [31:0] node_count,
                                         input logic [31:0] list_count);
  node_check = node_decide(node_sums(rec), own, node_count, list_count);
endfunction

// The error bits (rc_pkg::CoreStatus*) that visiting a node with these checks and these active
// rays raises; none without active rays (such an entry is not visited).
function automatic logic [2:0] walk_err(input logic [3:0] mask, input logic [1:0] chk);
  walk_err = 3'd0;
  walk_err[CoreStatusMalformedNode] = (mask != 4'd0) && chk == NodeMalformed;
  walk_err[CoreStatusBadAddress]    = (mask != 4'd0) && chk == NodeBadList;
endfunction

// The unit a walk entry goes to (Route*), from its active rays and its node's kind, value (a
// leaf's triangle count) and checks.
function automatic logic [1:0] walk_route(input logic [3:0] mask, input logic [1:0] kind,
                                          input logic [31:0] upper, input logic [1:0] chk);
  if (mask == 4'd0 || chk != NodeOk) begin
    walk_route = RoutePop;
  end else if (kind != 2'(KdNodeKindLeaf)) begin
    walk_route = RouteTrav;
  end else begin
    walk_route = (upper != 32'd0) ? RouteLeaf : RoutePop;
  end
endfunction

// The lowest ray of a four-ray mask (0 for an empty mask).
function automatic logic [1:0] ray_lowest(input logic [3:0] m);
  if (m[0]) begin
    ray_lowest = 2'd0;
  end else if (m[1]) begin
    ray_lowest = 2'd1;
  end else if (m[2]) begin
    ray_lowest = 2'd2;
  end else begin
    ray_lowest = m[3] ? 2'd3 : 2'd0;
  end
endfunction

// The number of rays in a four-ray mask.
function automatic logic [2:0] ray_count(input logic [3:0] m);
  ray_count = 3'(m[0]) + 3'(m[1]) + 3'(m[2]) + 3'(m[3]);
endfunction

// Ray i's 32-bit word of a four-ray vector (ray r at [32 r +: 32]): a 4:1 multiplexer.
function automatic logic [31:0] lane32(input logic [127:0] v, input logic [1:0] i);
  lane32 = '0;
  for (int unsigned r = 0; r < 4; r++) if (i == 2'(r)) lane32 = v[r*32 +: 32];
endfunction
