//! `host-sim serve`: the browser page and runs to replay, served on 127.0.0.1 ([`crate::serve`]).

use std::io::Write as _;

use crate::serve::{ServeArgs, Server};

/// `host-sim serve`: binds, prints where, serves until interrupted.
///
/// # Errors
/// See [`Server::bind`].
pub fn run(args: &ServeArgs) -> anyhow::Result<()> {
    let server = Server::bind(args)?;
    println!("{}; Ctrl-C stops", server.banner()?);
    std::io::stdout().flush()?;
    server.run();
    Ok(())
}
