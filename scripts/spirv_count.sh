# count_spirv FILE.spvasm: prints "body alu tex cond module" for a SPIR-V disassembly, by the
# counting rule described in scripts/bench_interior.sh (instructions between OpFunction and
# OpFunctionEnd, structure annotations excluded; alu excludes data movement and plumbing).
# Sourced by scripts/bench_interior.sh and scripts/im_trace_spirv.sh.
count_spirv() {   # $1 = disassembly file
  awk '
    /^[[:space:]]*(%[^ ]+ = )?Op/ { module++ }
    { line = $0; sub(/^[[:space:]]*%[^ ]+ = /, "", line); sub(/^[[:space:]]+/, "", line); split(line, w, " "); op = w[1] }
    op == "OpFunction" { inside = 1; next }
    op == "OpFunctionEnd" { inside = 0; next }
    inside && op ~ /^Op/ {
      if (op ~ /^(OpLabel|OpFunctionParameter|OpLine|OpNoLine|OpSelectionMerge|OpLoopMerge)$/) next
      body++
      if (op ~ /^(OpImageSample|OpImageFetch|OpImageGather|OpImageQuery)/) tex++
      if (op ~ /^(OpBranchConditional|OpSwitch)$/) cond++
      if (op !~ /^(OpLoad|OpStore|OpAccessChain|OpInBoundsAccessChain|OpVectorShuffle|OpCompositeConstruct|OpCompositeExtract|OpCompositeInsert|OpCopyObject|OpUndef|OpSampledImage|OpBranch|OpReturn|OpReturnValue|OpKill|OpPhi|OpImageSample.*|OpImageFetch|OpImageGather|OpImageQuery.*|OpBranchConditional|OpSwitch)$/) alu++
    }
    END { printf "%d %d %d %d %d\n", body, alu, tex + 0, cond + 0, module }' "$1"
}
