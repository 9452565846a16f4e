//! Evens out the parts METIS leaves over the size limit. With contiguous
//! parts of a few dozen triangles METIS can miss its imbalance by a
//! triangle or two; moving boundary triangles into a smaller neighbouring
//! part fixes that without giving up connected parts, and the order of
//! the moves depends on the triangle numbers alone, so it is deterministic.

/// Moves triangles out of every part above `limit` until none is: along
/// the shortest chain of touching parts from the full part to one with
/// room, each part hands one border triangle to the next, last link
/// first, so only the two ends change size. A part hands over its
/// lowest-numbered triangle next to the receiving part whose removal
/// keeps it connected (the receiver, touching it, stays connected too; on
/// a disconnected net, whose parts need not be connected, any will do).
/// Returns false when some part stays over.
pub(super) fn rebalance(
    start: &[u32],
    adj: &[u32],
    part: &mut [u32],
    k: usize,
    limit: usize,
    contig: bool,
) -> bool {
    let mut sizes = vec![0usize; k];
    for &p in part.iter() {
        sizes[p as usize] += 1;
    }
    for p in 0..k as u32 {
        while sizes[p as usize] > limit {
            let Some(chain) = chain_to_room(start, adj, part, &sizes, p, limit) else {
                return false;
            };
            for pair in chain.windows(2).rev() {
                let (from, to) = (pair[0], pair[1]);
                let Some(t) = movable(start, adj, part, from, to, contig) else {
                    return false;
                };
                part[t] = to;
            }
            sizes[p as usize] -= 1;
            sizes[*chain.last().unwrap() as usize] += 1;
        }
    }
    true
}

/// The shortest chain of touching parts from `p` to a part below `limit`
/// (breadth first, neighbours in part order).
fn chain_to_room(
    start: &[u32],
    adj: &[u32],
    part: &[u32],
    sizes: &[usize],
    p: u32,
    limit: usize,
) -> Option<Vec<u32>> {
    let k = sizes.len();
    let mut touching = vec![std::collections::BTreeSet::new(); k];
    for t in 0..part.len() {
        for &s in &adj[start[t] as usize..start[t + 1] as usize] {
            if part[s as usize] != part[t] {
                touching[part[t] as usize].insert(part[s as usize]);
            }
        }
    }
    let mut from = vec![u32::MAX; k];
    from[p as usize] = p;
    let mut queue = std::collections::VecDeque::from([p]);
    while let Some(a) = queue.pop_front() {
        if sizes[a as usize] < limit {
            let mut chain = vec![a];
            while *chain.last().unwrap() != p {
                chain.push(from[*chain.last().unwrap() as usize]);
            }
            chain.reverse();
            return Some(chain);
        }
        for &b in &touching[a as usize] {
            if from[b as usize] == u32::MAX {
                from[b as usize] = a;
                queue.push_back(b);
            }
        }
    }
    None
}

/// The lowest-numbered triangle of part `from` next to part `to` whose
/// removal leaves `from` in one piece.
fn movable(
    start: &[u32],
    adj: &[u32],
    part: &[u32],
    from: u32,
    to: u32,
    contig: bool,
) -> Option<usize> {
    let members: Vec<usize> = (0..part.len()).filter(|&t| part[t] == from).collect();
    members.iter().copied().find(|&t| {
        adj[start[t] as usize..start[t + 1] as usize]
            .iter()
            .any(|&s| part[s as usize] == to)
            && (!contig || stays_connected(start, adj, part, &members, t))
    })
}

/// Whether `members` (one part) without `t` is still one piece.
fn stays_connected(start: &[u32], adj: &[u32], part: &[u32], members: &[usize], t: usize) -> bool {
    let p = part[t];
    let Some(&first) = members.iter().find(|&&s| s != t) else {
        return true;
    };
    let mut seen = std::collections::HashSet::from([t, first]);
    let mut stack = vec![first];
    while let Some(s) = stack.pop() {
        for &u in &adj[start[s] as usize..start[s + 1] as usize] {
            let u = u as usize;
            if part[u] == p && seen.insert(u) {
                stack.push(u);
            }
        }
    }
    seen.len() == members.len()
}
