// Times the WebAssembly decoder in headless Chromium on .eqm streams (web/bench/
// run_bench.sh extracts them from encoded .glb files), each in a fresh page: a first decode (timed apart), then RUNS
// timed decodes of the whole stream, median and minimum. Prints one JSON line per
// stream. Not a test: speed targets live in bench/, never in timed tests.
//   node tests/web/bench_decode.mjs RUNS STREAM.eqm ...   (streams inside the repo)
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startStaticServer } from './static_server.mjs';

const ROOT = path.resolve( path.dirname( fileURLToPath( import.meta.url ) ), '../..' );
const [ runs, ...streams ] = process.argv.slice( 2 );
const served = ( file ) => '/' + path.relative( ROOT, path.resolve( file ) ).split( path.sep ).join( '/' );

const server = await startStaticServer( ROOT );
const browser = await chromium.launch( {
	executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
	args: [ '--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking',
		'--use-angle=swiftshader', '--enable-unsafe-swiftshader' ],
} );
try {

	// A fresh page per stream: its first decode is what a visitor waits for.
	for ( const stream of streams ) {

		const page = await browser.newPage();
		await page.goto( `${server.url}/samples/web/?model=none.glb` );
		const result = await page.evaluate( timeDecodes, { url: served( stream ), runs: Number( runs ) } );
		console.log( JSON.stringify( { stream: path.basename( stream ), ...result } ) );
		await page.close();

	}

} finally {

	await browser.close();
	server.server.close();

}

async function timeDecodes( { url, runs } ) {

	const decoder = await window.eqmeshDemo.decoder;
	const bytes = new Uint8Array( await ( await fetch( url ) ).arrayBuffer() );
	const t0 = performance.now();
	const first = decoder.decode( bytes );
	const first_ms = performance.now() - t0; // the page's first: fresh heap pages, code not yet optimised
	const ms = [];
	for ( let i = 0; i < runs; i ++ ) {

		const start = performance.now();
		decoder.decode( bytes );
		ms.push( performance.now() - start );

	}
	ms.sort( ( a, b ) => a - b );
	return { vertices: first.positions.length / 3, triangles: first.indices.length / 3,
		first_ms, median_ms: ms[ ms.length >> 1 ], min_ms: ms[ 0 ] };

}
